#!/usr/bin/env python3
"""Doxygen INPUT_FILTER for the public headers: the house comments are plain
``//`` text written for a reader of the header, so this turns them into
Doxygen documentation without changing the headers.

* The comment block that opens a file documents the file (``@file``).
* A comment block directly above a declaration at namespace or class scope
  documents that declaration; a trailing ``// text`` after a member or an
  enumerator documents it (``///<``).
* At namespace scope, a comment above several declarations with no blank
  line between them (overloads, a family of conversions) documents each of
  them: functions, variables and aliases through a Doxygen member group
  (DISTRIBUTE_GROUP_DOC); a later class, or the members after a class,
  which Doxygen does not group, get "See FIRST above."
* Comments inside function bodies, and blocks followed by a blank line
  (section notes), stay plain comments.

Multi-line blocks are kept verbatim (their alignment carries equations and
lists); one-line comments become text with Doxygen's special characters
escaped.  The output has the same number of lines as the input, so Doxygen's
line numbers are the header's.
"""
import re
import sys

SCOPE = re.compile(r"\b(namespace|struct|class|enum|union)\b|extern\s+\"C\"")
GROUP_END = "/**@}*/ "
CLASS_LIKE = re.compile(r"^\s*(?:template\s*<.*>\s*)?(?:struct|class|union|enum)\b")
SPECIAL = re.compile(r'([\\@&$#<>%"])')


def escaped(text):
    return SPECIAL.sub(r"\\\1", text)


def comment_text(line):
    """The text of a whole-line // comment (one leading space dropped)."""
    body = line.strip()[2:].lstrip("/!")
    return body[1:] if body.startswith(" ") else body


def structured(texts):
    """Whether a block's layout carries meaning: indented or bulleted lines,
    or columns aligned with runs of spaces."""
    return any(t.startswith((" ", "* ", "- ")) or re.search(r"\S {3,}\S", t) for t in texts[1:]) or \
        bool(texts and texts[0].startswith(("* ", "- ")))


def documentation(texts, command=""):
    """The lines of a Doxygen comment holding `texts`, one for one; `command`
    (@file) goes last, where its optional argument is empty."""
    tail = (" " + command if command else "") + " */"
    if structured(texts):
        texts = [t.replace("endverbatim", "end verbatim") for t in texts]
        texts[0] = "/** @verbatim " + texts[0]
        texts[-1] += " @endverbatim" + tail
        return texts
    texts = [escaped(t) for t in texts]
    texts[0] = "/** " + texts[0]
    texts[-1] += tail
    return texts


def strip_strings(code):
    return re.sub(r'"(\\.|[^"\\])*"', '""', code)


def split_trailing(line):
    """(code, comment) of a line with code and a trailing // comment, found
    outside string and character literals; (line, None) without one."""
    quote = None
    i = 0
    while i < len(line):
        c = line[i]
        if quote:
            if c == "\\":
                i += 1
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif line.startswith("//", i):
            return (line[:i], line[i:]) if line[:i].strip() else (line, None)
        i += 1
    return line, None


class Run:
    """Declarations that follow one documentation block without a blank line."""

    def __init__(self, first_comment_line, depth):
        self.first_comment_line = first_comment_line
        self.depth = depth
        self.declarations = 0
        self.last_line = None
        self.closed_body = False  # a } just ended an inline body at this depth
        self.starts = []          # (line, text) where each declaration begins


IDENTIFIER = re.compile(r"[A-Za-z_]\w*")


def declared_name(text):
    """The name a declaration's first line declares: struct X, using X =,
    the function before its '(', the variable before '=', '{' or ';'."""
    text = re.sub(r"/\*.*?\*/", "", text).strip()
    match = re.match(r"^(?:struct|class|union|enum(?:\s+class)?)\s+(\w+)", text) or \
        re.match(r"^using\s+(\w+)\s*=", text)
    if match:
        return match.group(1)
    head = re.split(r"[(={;]", text, 1)[0]
    names = IDENTIFIER.findall(head.replace("operator", ""))
    return names[-1] if names else None


def filter_lines(lines):
    out = []
    stack = []          # True for a scope whose comments are documentation
    kinds = []          # its kind: namespace, class (struct, enum, union) or body
    statement = ""      # code since the last ; { or }
    block = []          # pending whole-line comment block (indices into out)
    seen_code = False
    run = None

    def in_doc_scope():
        return all(stack)

    def end_run(at_line):
        """Closes the run before the line `at_line` of `out` (a blank line, a
        comment, a directive or the scope's closing brace; None: the end)."""
        nonlocal run
        if run and len(run.starts) > 1:
            first_line, first_text = run.starts[0]
            name = declared_name(first_text)
            classes = [CLASS_LIKE.match(text) is not None for _, text in run.starts]
            for k, (line, text) in enumerate(run.starts[1:], 1):
                # Doxygen distributes a group's documentation only from member to member.
                if name and (classes[0] or classes[k]) and "/**" not in out[line]:
                    indent = out[line][: len(out[line]) - len(out[line].lstrip())]
                    out[line] = indent + f"/** See {name} above. */ " + out[line].lstrip()
        if run and run.declarations > 1:
            first = out[run.first_comment_line]
            closes = first.startswith(GROUP_END)  # the run before ends on this line too
            first = first[len(GROUP_END):] if closes else first
            out[run.first_comment_line] = (GROUP_END if closes else "") + first.replace("/**", "/**@{*/ /**", 1)
            if at_line is None:
                out.append("/**@}*/")
            else:
                out[at_line] = GROUP_END + out[at_line]
        run = None

    def flush_block(documents):
        nonlocal block, run
        if block:
            # A group's end marker may stand before the first comment line (end_run).
            closer = out[block[0]].startswith(GROUP_END)
            if closer:
                out[block[0]] = out[block[0]][len(GROUP_END):]
            texts = [comment_text(out[i]) for i in block]
            indent = out[block[0]][: len(out[block[0]]) - len(out[block[0]].lstrip())]
            if documents == "file":
                new = documentation(texts, "@file")
            elif documents:
                new = documentation(texts)
                if all(kind == "namespace" for kind in kinds):
                    run = Run(block[0], len(stack))
            else:
                new = None
            if new:
                for i, text in zip(block, new):
                    out[i] = indent + text
            if closer:
                out[block[0]] = GROUP_END + out[block[0]]
        block = []

    for raw in lines:
        line = raw.rstrip("\n")
        stripped = line.strip()
        if stripped.startswith("//"):
            out.append(line)
            end_run(len(out) - 1)
            if in_doc_scope() or not seen_code:
                block.append(len(out) - 1)
            continue
        if not stripped or stripped.startswith("#"):
            flush_block("file" if not seen_code else False)
            if stripped.startswith("#"):
                seen_code = seen_code or not stripped.startswith("#pragma")
            out.append(line)
            end_run(len(out) - 1)
            continue
        # A code line: a pending block documents it when the scope is one of declarations.
        flush_block(in_doc_scope())
        seen_code = True
        code, trailing = split_trailing(line)
        if run and len(stack) == run.depth and not statement.strip():
            if run.starts and run.starts[-1][1].lstrip().startswith("template"):
                run.starts[-1] = (run.starts[-1][0], run.starts[-1][1] + " " + code)  # template <...> + its line
            else:
                run.starts.append((len(out), code))
        if trailing and in_doc_scope() and re.search(r"[;,]\s*$", code.rstrip()) and not re.match(r"^\s*}", code):
            text = comment_text(trailing.strip())
            line = code + "///< " + escaped(text)
        elif trailing and in_doc_scope() and SCOPE.search(code) and code.rstrip().endswith("{"):
            # struct GammaDrops {  // n ~ r^alpha ...: the comment documents the struct
            indent = code[: len(code) - len(code.lstrip())]
            line = indent + "/** " + escaped(comment_text(trailing.strip())) + " */ " + code.lstrip().rstrip()
        out.append(line)
        for ch in strip_strings(code):
            if ch == "{":
                scope = SCOPE.search(statement)
                stack.append(bool(scope) and "(" not in statement.split("enum")[0])
                kinds.append("namespace" if scope and scope.group(1) == "namespace" else "class" if stack[-1] else "body")
                statement = ""
            elif ch == "}":
                if stack:
                    stack.pop()
                    kinds.pop()
                statement = ""
                if run and len(stack) < run.depth:
                    end_run(len(out) - 1)
                elif run and len(stack) == run.depth:
                    run.declarations += 1
                    run.last_line = len(out) - 1
                    run.closed_body = True
                    continue
            elif ch == ";":
                statement = ""
                if run and len(stack) == run.depth:
                    if not run.closed_body:
                        run.declarations += 1
                    run.last_line = len(out) - 1
            else:
                statement += ch
            if run and not ch.isspace():
                run.closed_body = False
        statement += " "
    end_run(None)
    flush_block(False)
    return out


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        lines = f.readlines()
    sys.stdout.write("\n".join(filter_lines(lines)) + "\n")


if __name__ == "__main__":
    main()
