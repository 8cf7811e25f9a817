"""The Examples in the package's docstrings run and print what they show
(doctest over every module of the package, found on disk so that a new
module is covered without listing it), and the public names of the modules
written in numpy style keep the sections a documentation build renders."""

import doctest
import importlib
import inspect
import pkgutil

import pytest

import attenuvis

MODULES = ["attenuvis"] + sorted(name for _, name, _ in pkgutil.walk_packages(attenuvis.__path__, "attenuvis."))

# Lenient only where the output is the same in substance: "..." stands for
# any text and runs of white space compare equal (NumPy's array printing
# wraps lines by width).  An example may still say so itself, as
# `# doctest: +ELLIPSIS`, so that it runs the same under other doctest runners.
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def test_every_module_is_found():
    assert {"attenuvis", "attenuvis.mie", "attenuvis.visgraph", "attenuvis.weather"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name, capsys):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=FLAGS, report=True)
    # testmod writes each failure (example, expected, got) to stdout.
    assert result.failed == 0, capsys.readouterr().out


def public_objects(module):
    """(qualified name, object) of every public name in __all__ and of the
    public methods a class defines itself (not its NamedTuple fields)."""
    for name in module.__all__:
        obj = getattr(module, name)
        if inspect.ismodule(obj) or not (inspect.isclass(obj) or callable(obj)):
            continue
        yield f"{module.__name__}.{name}", obj
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                member = getattr(member, "__func__", member)  # classmethod
                if inspect.isfunction(member):
                    yield f"{module.__name__}.{name}.{attr}", member


def section_headers(doc):
    """Names of the numpy-style section headers (a line underlined by dashes)."""
    lines = inspect.cleandoc(doc).splitlines()
    return {lines[i].strip() for i in range(len(lines) - 1)
            if lines[i].strip() and set(lines[i + 1].strip()) == {"-"} and
            len(lines[i + 1].strip()) == len(lines[i].strip())}


@pytest.mark.parametrize("module", [attenuvis.mie, attenuvis.visgraph], ids=lambda m: m.__name__)
def test_public_names_have_numpy_sections(module):
    for name, obj in public_objects(module):
        headers = section_headers(obj.__doc__ or "")
        assert "Examples" in headers, f"{name}: no Examples section"
        if inspect.isfunction(obj):
            takes_arguments = any(p.name not in ("self", "cls") for p in inspect.signature(obj).parameters.values())
            assert not takes_arguments or "Parameters" in headers, f"{name}: no Parameters section"
            assert "Returns" in headers, f"{name}: no Returns section"
