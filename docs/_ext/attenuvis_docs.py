"""Sphinx extension of the attenuvis documentation.

Directives (used in MyST pages as ```{name} ...```):

``attenuvis-help ARGS``
    The text that ``attenuvis ARGS`` prints (``vg --help``, ``help conditions``),
    run from the built program, so the reference cannot drift from it.
``attenuvis-cli-reference``
    One section per subcommand that ``attenuvis --help`` lists, each holding
    that subcommand's ``--help``: the command-line reference and the man page.
``attenuvis-cpp-headers MODULE``
    One section per public header of MODULE found in Doxygen's XML (so a new
    header joins the reference without an edit), rendered by breathe.
``attenuvis-example SCRIPT``
    An ``examples/`` script: its source, what it printed and the figures it
    drew when the documentation was built (the scripts run once per build).

Checks, reported as warnings (the build runs with -W, so they fail it):

* every name in ``__all__`` of the Python package's modules is documented by
  autodoc and has a docstring;
* every declaration at namespace scope in the public C++ headers has a
  comment (class members, nested classes among them, are covered by their
  class's comment), and every public header an opening comment;
* the HTML loads nothing from the network (no script, style sheet, font or
  image from another host).
"""
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

from docutils import nodes
from docutils.parsers.rst import Directive, directives
from docutils.statemachine import StringList
from sphinx.errors import ExtensionError
from sphinx.util import logging

logger = logging.getLogger(__name__)

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_ROOT = os.path.dirname(os.path.dirname(HERE))


# ---------------------------------------------------------------- the program

def program(env):
    path = env.config.attenuvis_program
    if not path or not os.access(path, os.X_OK):
        raise ExtensionError(f"ATTENUVIS_CLI must name the built attenuvis program (got {path!r})")
    env.note_dependency(path)
    return path


# Paths that --help prints for the tree it runs from (the build tree's HTML, or
# the Markdown sources) are shown as the installed program prints them with
# the default prefix: file:///usr/local/share/doc/attenuvis/html/PAGE.html.
DOCS_PATH = re.compile(r"(?:file://)?/\S*/(?:html|docs)/(\S+?)\.(?:html|md)\b")


def run_program(env, args):
    result = subprocess.run(["attenuvis"] + args, executable=program(env), capture_output=True, text=True,
                            timeout=60, env={**os.environ, "COLUMNS": "100"})
    if result.returncode != 0:
        raise ExtensionError(f"attenuvis {' '.join(args)} failed ({result.returncode}): {result.stderr.strip()}")
    return DOCS_PATH.sub(r"file:///usr/local/share/doc/attenuvis/html/\1.html", result.stdout).rstrip() + "\n"


def literal(text, language="text"):
    block = nodes.literal_block(text, text)
    block["language"] = language
    return block


class HelpDirective(Directive):
    required_arguments = 1
    final_argument_whitespace = True

    def run(self):
        env = self.state.document.settings.env
        args = self.arguments[0].split()
        return [literal(run_program(env, args))]


def subcommands(env):
    """(name, summary) of every subcommand, in the order --help lists them
    (a summary may continue on indented lines)."""
    text = run_program(env, ["--help"])
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith("Subcommands:"):
            inside = True
            continue
        if inside:
            match = re.match(r"^  (\S+)\s+(.*)$", line)
            if match:
                out.append(list(match.groups()))
            elif line.startswith("    ") and out:
                out[-1][1] += " " + line.strip()
            elif line.strip() == "":
                break
    if not out:
        raise ExtensionError("attenuvis --help lists no subcommands")
    return out


class CliReferenceDirective(Directive):
    """A section per subcommand with its --help."""

    def run(self):
        env = self.state.document.settings.env
        result = []
        for name, _ in subcommands(env):
            section = nodes.section(ids=[f"attenuvis-{name}"], names=[f"attenuvis {name}"])
            section += nodes.title(text=f"attenuvis {name}")
            section += literal(run_program(env, [name, "--help"]))
            self.state.document.note_implicit_target(section)
            result.append(section)
        return result


# ------------------------------------------------------------- C++ reference

def doxygen_xml(config):
    path = config.breathe_projects.get("attenuvis", "")
    if not path or not os.path.isfile(os.path.join(path, "index.xml")):
        raise ExtensionError(f"ATTENUVIS_DOXYGEN_XML must name Doxygen's XML of the public headers (got {path!r})")
    return path


def public_headers(config):
    """Paths of the public headers as Doxygen names them (attenuvis/mie.hpp)."""
    root = ET.parse(os.path.join(doxygen_xml(config), "index.xml")).getroot()
    files = []
    for compound in root.findall("compound"):
        if compound.get("kind") == "file":
            xml = ET.parse(os.path.join(doxygen_xml(config), compound.get("refid") + ".xml")).getroot()
            files.append(xml.find("compounddef/location").get("file"))
    return sorted(files)


def module_of(header):
    """attenuvis/mie.hpp and attenuvis/mie/x.hpp belong to module mie."""
    parts = header.split("/")
    return parts[1][: -len(".hpp")] if len(parts) == 2 else parts[1]


def namespaces_of(config, module):
    """attenuvis::MODULE and the namespaces inside it, detail ones left out."""
    root = ET.parse(os.path.join(doxygen_xml(config), "index.xml")).getroot()
    names = [c.findtext("name") for c in root.findall("compound") if c.get("kind") == "namespace"]
    prefix = f"attenuvis::{module}"
    return sorted(n for n in names if (n == prefix or n.startswith(prefix + "::")) and "detail" not in n.split("::"))


class CppHeadersDirective(Directive):
    """The public headers of a module, each with its opening comment, then
    every declaration of its namespaces with its comment."""
    required_arguments = 1

    def run(self):
        env = self.state.document.settings.env
        module = self.arguments[0]
        headers = [h for h in public_headers(env.config) if module_of(h) == module]
        if not headers:
            raise self.error(f"no public header of module {module} in Doxygen's XML")
        lines = ["## Headers", ""]
        for header in headers:
            lines += [f"### `{header}`", "", f"```{{doxygenfile}} {header}", ":project: attenuvis",
                      ":sections: briefdescription detaileddescription", "```", ""]
        for namespace in namespaces_of(env.config, module):
            lines += [f"## `{namespace}`", "", f"```{{doxygennamespace}} {namespace}", ":project: attenuvis",
                      ":content-only:", ":members:", ":undoc-members:", "```", ""]
        container = nodes.section()
        container.document = self.state.document
        self.state.nested_parse(StringList(lines, source=env.docname), self.content_offset, container,
                                match_titles=True)
        return container.children


def has_description(element):
    for tag in ("briefdescription", "detaileddescription"):
        found = element.find(tag)
        if found is not None and "".join(found.itertext()).strip():
            return True
    return False


def check_cpp_comments(app):
    """Warns for each declaration at namespace scope without a comment."""
    xml_dir = doxygen_xml(app.config)
    root = ET.parse(os.path.join(xml_dir, "index.xml")).getroot()
    classes = {c.findtext("name") for c in root.findall("compound") if c.get("kind") in ("class", "struct", "union")}
    for compound in root.findall("compound"):
        kind = compound.get("kind")
        if kind not in ("namespace", "class", "struct", "union", "file"):
            continue
        definition = ET.parse(os.path.join(xml_dir, compound.get("refid") + ".xml")).getroot().find("compounddef")
        name = definition.findtext("compoundname")
        if "detail" in name.split("::"):
            continue
        location = definition.find("location")
        if kind == "file" and not has_description(definition):
            logger.warning(f"public header {name} has no opening comment saying what it holds",
                           location=(location.get("file"), 1))
        nested = name.rsplit("::", 1)[0] in classes  # a member of a class: the class's comment covers it
        if kind in ("class", "struct", "union") and definition.get("prot") == "public" and not nested and \
                not has_description(definition):
            logger.warning(f"C++ {kind} {name} has no comment", location=(location.get("file"),
                                                                         int(location.get("line", 0))))
        if kind != "namespace":
            continue
        for member in definition.iter("memberdef"):
            if not has_description(member):
                where = member.find("location")
                logger.warning(f"C++ {member.get('kind')} {name}::{member.findtext('name')} has no comment",
                               location=(where.get("file"), int(where.get("line", 0))))


# ------------------------------------------------------------------ examples

def examples_output(app):
    return os.path.join(app.config.attenuvis_generated, "examples")


def run_examples(app):
    """Runs every examples/*.py once per build into the generated directory."""
    if app.builder.format != "html":
        return
    out = examples_output(app)
    shutil.rmtree(out, ignore_errors=True)
    scripts = sorted(s for s in os.listdir(os.path.join(SOURCE_ROOT, "examples")) if s.endswith(".py"))

    def run_one(script):
        target = os.path.join(out, script[: -len(".py")])
        os.makedirs(target)
        result = subprocess.run([sys.executable, os.path.join(SOURCE_ROOT, "examples", script), target],
                                capture_output=True, text=True, timeout=600,
                                env={**os.environ, "MPLBACKEND": "Agg"})
        return script, target, result

    # The scripts are independent processes: side by side, as many as there
    # are cores (each writes only its own directory).
    logger.info(f"running examples/{', '.join(scripts)}")
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        for script, target, result in pool.map(run_one, scripts):
            if result.returncode != 0:
                raise ExtensionError(f"examples/{script} failed ({result.returncode}):\n{result.stderr}")
            with open(os.path.join(target, "stdout.txt"), "w") as f:
                f.write(result.stdout.replace(target, "OUTDIR"))


class ExampleDirective(Directive):
    required_arguments = 1
    option_spec = {"figure-width": directives.unchanged}

    def run(self):
        env = self.state.document.settings.env
        script = self.arguments[0]
        path = os.path.join(SOURCE_ROOT, "examples", script)
        env.note_dependency(path)
        with open(path) as f:
            source = f.read()
        script_part = [nodes.paragraph(text=f"The script, examples/{script}:"), literal(source, "python")]
        if env.app.builder.format != "html":
            return script_part
        target = os.path.join(examples_output(env.app), script[: -len(".py")])
        result = []
        # What it drew, then what it printed, then how.
        for figure in sorted(os.listdir(target)):
            if figure.endswith(".png"):
                # A path from the source directory, written as Sphinx reads "/..." (relative to it).
                uri = "/" + os.path.relpath(os.path.join(target, figure), env.srcdir)
                image = nodes.image(uri=uri, alt=f"{figure}, drawn by examples/{script}")
                image["width"] = self.options.get("figure-width", "100%")
                result.append(image)
        with open(os.path.join(target, "stdout.txt")) as f:
            printed = f.read()
        if printed.strip():
            result += [nodes.paragraph(text="It printed:"), literal(printed)]
        return result + script_part


# ------------------------------------------------------------ Python names

def check_python_names(app, env):
    """Every public name of the package is documented, with a docstring."""
    import importlib

    objects = env.get_domain("py").objects
    package = importlib.import_module("attenuvis")
    for module_name in ["attenuvis"] + [f"attenuvis.{m}" for m in package.__all__ if m != "__version__"]:
        module = importlib.import_module(module_name)
        if module_name != "attenuvis" and not module.__doc__:
            logger.warning(f"Python module {module_name} has no docstring")
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if name == "__version__" or type(obj).__name__ == "module":
                continue
            qualified = f"{module_name}.{name}"
            if qualified not in objects:
                logger.warning(f"Python name {qualified} is public (__all__) but not in the reference")
            elif not (getattr(obj, "__doc__", None) or "").strip():
                logger.warning(f"Python name {qualified} has no docstring")


# ------------------------------------------------------------------ offline

REMOTE = re.compile(r"""<(?:script|link|img|iframe)\b[^>]*\b(?:src|href)\s*=\s*["'](?:https?:)?//""", re.I)
REMOTE_CSS = re.compile(r"""url\(\s*["']?(?:https?:)?//|@import\s+["']?(?:url\()?\s*["']?(?:https?:)?//""", re.I)


def check_offline(app, exception):
    if exception or app.builder.format != "html":
        return
    for folder, _, files in os.walk(app.outdir):
        for name in files:
            path = os.path.join(folder, name)
            if name.endswith(".html"):
                pattern = REMOTE
            elif name.endswith(".css"):
                pattern = REMOTE_CSS
            else:
                continue
            with open(path, encoding="utf-8", errors="replace") as f:
                for number, line in enumerate(f, 1):
                    if pattern.search(line):
                        logger.warning(f"loads from the network: {line.strip()[:160]}", location=(path, number))


def always_outdated(app, env, added, changed, removed):
    """Pages whose content comes from the program, the headers or the
    examples (they use a directive of this extension) are read again on
    every build."""
    out = []
    for doc in env.found_docs:
        with open(env.doc2path(doc), encoding="utf-8") as f:
            if "{attenuvis-" in f.read():
                out.append(doc)
    return out


def setup(app):
    app.add_config_value("attenuvis_program", os.environ.get("ATTENUVIS_CLI", ""), "env")
    app.add_config_value("attenuvis_generated",
                         os.environ.get("ATTENUVIS_DOCS_GENERATED", os.path.join(SOURCE_ROOT, "build", "docs")),
                         "env")
    app.add_directive("attenuvis-help", HelpDirective)
    app.add_directive("attenuvis-cli-reference", CliReferenceDirective)
    app.add_directive("attenuvis-cpp-headers", CppHeadersDirective)
    app.add_directive("attenuvis-example", ExampleDirective)
    app.connect("builder-inited", run_examples)
    app.connect("builder-inited", check_cpp_comments)
    app.connect("env-check-consistency", check_python_names)
    app.connect("env-get-outdated", always_outdated)
    app.connect("build-finished", check_offline)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
