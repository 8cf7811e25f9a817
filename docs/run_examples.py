#!/usr/bin/env python3
"""Runs every code block of the documentation and checks what it prints.

    run_examples.py --work DIR [--cxx CMD --cxx-libs LIBS] [--list] FILE_OR_DIR...

A fenced block in a Markdown page (```sh, ```python or ```cpp) is run unless
the comment line right above it says why not:

    % not run: REASON                 (MyST comment; in README.md: <!-- not run: REASON -->)

and every block that runs states what it must print, one or more lines above
the fence:

    % expect: TEXT                    the block's output (stdout and stderr) contains TEXT
    % expect in FILE: TEXT            the file FILE, written by the block, contains TEXT

A block that runs without an expectation, an unknown language, a failing
command, a missing text or a block that runs past its time is a failure.
Blocks of other languages (text, csv, json, cdl) are outputs and file
listings, not examples.  The blocks of one page run in order in one working
directory (a block may use what an earlier one wrote); its Python blocks
share one namespace.  Shell blocks find `attenuvis` on PATH (ctest puts the
build tree's program first) and run under bash -euo pipefail.
"""
import argparse
import contextlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import traceback

RUN = {"sh": "sh", "bash": "sh", "python": "python", "cpp": "cpp"}
OUTPUT = {"text", "csv", "json", "cdl", "console-output", "none"}
FENCE = re.compile(r"^(?P<indent> *)(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
MARKER = re.compile(r"^\s*(?:%|<!--)\s*(?P<key>not run|expect(?: in (?P<file>\S+))?)\s*:\s*(?P<value>.*?)\s*(?:-->)?\s*$")
# README's two set-up commands are the ones that run these checks.
SETUP_COMMANDS = {"bash scripts/main.sh", "bash scripts/test.sh"}
TIMEOUT_S = 300


class Block:
    def __init__(self, path, line, language, text, markers):
        self.path, self.line, self.language, self.text = path, line, language, text
        self.not_run = next((value for key, _, value in markers if key == "not run"), None)
        self.expect = [(file, value) for key, file, value in markers if key.startswith("expect")]

    @property
    def where(self):
        return f"{self.path}:{self.line}"


def blocks_of(path):
    """The fenced code blocks of a Markdown file with the markers above each."""
    lines = open(path, encoding="utf-8").read().splitlines()
    out, i = [], 0
    while i < len(lines):
        match = FENCE.match(lines[i])
        if not match:
            i += 1
            continue
        fence, info = match.group("fence"), match.group("info").strip()
        body, j = [], i + 1
        while j < len(lines) and not (lines[j].strip().startswith(fence) and lines[j].strip().strip(fence[0]) == ""):
            body.append(lines[j][len(match.group("indent")):])
            j += 1
        markers, k = [], i - 1
        while k >= 0 and MARKER.match(lines[k]):
            m = MARKER.match(lines[k])
            markers.insert(0, (m.group("key"), m.group("file"), m.group("value")))
            k -= 1
        if not info.startswith("{"):  # ```{directive} is MyST, not code
            out.append(Block(path, i + 1, info.split()[0] if info else "", "\n".join(body) + "\n", markers))
        i = j + 1
    return out


def markdown_files(arguments):
    for argument in arguments:
        if os.path.isdir(argument):
            for folder, dirs, files in sorted(os.walk(argument)):
                dirs[:] = sorted(d for d in dirs if not d.startswith(("_", ".")))
                yield from (os.path.join(folder, f) for f in sorted(files) if f.endswith(".md"))
        else:
            yield argument


class Page:
    """The working directory and Python namespace one page's blocks share."""

    def __init__(self, work, path, options):
        name = re.sub(r"[^A-Za-z0-9]+", "_", os.path.relpath(path, os.path.dirname(options.sources[0])))
        self.dir = os.path.join(work, name)
        shutil.rmtree(self.dir, ignore_errors=True)
        os.makedirs(self.dir)
        self.namespace = {"__name__": "__main__"}
        self.options = options

    def run(self, block):
        if block.language == "sh":
            return self.run_shell(block.text)
        if block.language == "python":
            return self.run_python(block.text)
        return self.run_cpp(block)

    def run_shell(self, text):
        result = subprocess.run(["bash", "-euo", "pipefail", "-c", text], cwd=self.dir, capture_output=True,
                                text=True, timeout=TIMEOUT_S)
        return result.returncode, result.stdout + result.stderr

    def run_python(self, text):
        captured = io.StringIO()
        cwd = os.getcwd()
        os.chdir(self.dir)
        try:
            with contextlib.redirect_stdout(captured), contextlib.redirect_stderr(captured):
                exec(compile(text, "<example>", "exec"), self.namespace)
            return 0, captured.getvalue()
        except Exception:
            return 1, captured.getvalue() + traceback.format_exc()
        finally:
            os.chdir(cwd)

    def run_cpp(self, block):
        if not self.options.cxx:
            return 1, "no C++ compiler given (--cxx)"
        source = os.path.join(self.dir, f"example_{block.line}.cpp")
        program = source[:-4]
        with open(source, "w") as f:
            f.write(block.text)
        command = shlex.split(self.options.cxx) + [source, "-o", program] + shlex.split(self.options.cxx_libs)
        built = subprocess.run(command, cwd=self.dir, capture_output=True, text=True, timeout=TIMEOUT_S)
        if built.returncode != 0:
            return built.returncode, " ".join(command) + "\n" + built.stdout + built.stderr
        result = subprocess.run([program], cwd=self.dir, capture_output=True, text=True, timeout=TIMEOUT_S)
        return result.returncode, result.stdout + result.stderr


def check(block, page):
    """None when the block ran and printed what it says, else why not."""
    status, output = page.run(block)
    if status != 0:
        return f"exit status {status}:\n{output}"
    for file, text in block.expect:
        if file:
            path = os.path.join(page.dir, file)
            if not os.path.isfile(path):
                return f"expected a file {file}; it was not written\n{output}"
            content = open(path, encoding="utf-8", errors="replace").read()
            if text not in content:
                return f"{file} does not contain {text!r}:\n{content[:2000]}"
        elif text not in output:
            return f"the output does not contain {text!r}:\n{output}"
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sources", nargs="+", help="Markdown files or directories of them")
    parser.add_argument("--work", required=True, help="working directory (one folder per page)")
    parser.add_argument("--cxx", default="", help="compiler command for C++ blocks, with include flags")
    parser.add_argument("--cxx-libs", default="", help="libraries C++ blocks link")
    parser.add_argument("--list", action="store_true", help="list the blocks and what is done with each")
    options = parser.parse_args()

    failures, counts, start = [], {"run": 0, "not run": 0, "output": 0}, time.monotonic()
    for path in markdown_files(options.sources):
        page = None
        for block in blocks_of(path):
            language = RUN.get(block.language)
            if language is None:
                if block.language not in OUTPUT:
                    failures.append((block, f"unknown language {block.language!r}: use sh, python or cpp for "
                                            f"an example, text (or csv, json, cdl) for an output"))
                counts["output"] += 1
                continue
            if block.not_run is not None or block.text.split("#")[0].strip() in SETUP_COMMANDS:
                reason = block.not_run or "the set-up command that runs these checks"
                if not reason:
                    failures.append((block, "'not run:' needs a reason"))
                counts["not run"] += 1
                if options.list:
                    print(f"{block.where}: {block.language}: not run: {reason}")
                continue
            block.language = language
            if not block.expect:
                failures.append((block, "a block that runs needs '% expect: TEXT' (what it must print) above it"))
                continue
            if options.list:
                print(f"{block.where}: {language}: expects {block.expect}")
                continue
            page = page or Page(options.work, path, options)
            began = time.monotonic()
            try:
                problem = check(block, page)
            except subprocess.TimeoutExpired:
                problem = f"ran longer than {TIMEOUT_S} s"
            counts["run"] += 1
            print(f"{block.where}: {language}: {'ok' if problem is None else 'FAILED'} "
                  f"({time.monotonic() - began:.1f} s)", flush=True)
            if problem:
                failures.append((block, problem))
    for block, problem in failures:
        print(f"\n{block.where}: {problem}\n--- the block:\n{block.text}", file=sys.stderr)
    print(f"{counts['run']} examples run, {counts['not run']} marked not run, {counts['output']} output listings; "
          f"{len(failures)} failed; {time.monotonic() - start:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
