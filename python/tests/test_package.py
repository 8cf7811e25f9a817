"""The package as a whole: version, docstrings on every public name, and an
import that does not need the optional xarray."""

import subprocess
import sys

import attenuvis
from attenuvis import mie, visgraph, weather


def test_version_is_the_project_version(source_dir):
    with open(source_dir / "CMakeLists.txt") as f:
        text = f.read()
    assert f"VERSION {attenuvis.__version__}" in text


def test_every_public_name_has_a_docstring():
    for module in (attenuvis, mie, weather, visgraph):
        assert module.__doc__
        for name in module.__all__:
            obj = getattr(module, name)
            if name != "__version__":
                assert obj.__doc__ and obj.__doc__.strip(), f"{module.__name__}.{name}"


def test_imports_without_xarray():
    code = ("import sys; sys.modules['xarray'] = None\n"
            "import attenuvis\n"
            "t = attenuvis.weather.table(['clear'], [550e-9])\n"
            "try:\n    t.to_xarray()\nexcept ImportError:\n    print('no xarray: ok')\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "no xarray: ok"
