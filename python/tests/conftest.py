"""Shared paths and helpers for the Python tests (run by ctest with the build
tree's package first on PYTHONPATH; ATTENUVIS_SOURCE_DIR and ATTENUVIS_CLI
come from ctest, with fallbacks for a direct pytest run)."""

import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("ATTENUVIS_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("ATTENUVIS_CLI", str(SOURCE_DIR / "build" / "apps" / "attenuvis"))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def cli():
    if not os.path.exists(CLI):
        pytest.skip(f"the attenuvis program is not built ({CLI})")
    return CLI


# A child interpreter runs `setup`, then `call`, and sends itself SIGINT one
# second after the call starts; it prints "interrupted after S s" when
# KeyboardInterrupt arrives S seconds after the signal, and exits 2 if the call
# ends first.
INTERRUPTED_CHILD = """
import os, signal, sys, threading, time
{setup}
sent = []
def interrupt():
    sent.append(time.monotonic())
    os.kill(os.getpid(), signal.SIGINT)
threading.Timer(1.0, interrupt).start()
try:
    {call}
    print("finished without interruption")
    sys.exit(2)
except KeyboardInterrupt:
    print(f"interrupted after {{time.monotonic() - sent[0]:.3f}} s")
"""


@pytest.fixture
def interrupted_child():
    """run(setup, call, timeout) -> the finished child (subprocess.CompletedProcess)."""
    def run(setup, call, timeout):
        code = INTERRUPTED_CHILD.format(setup=textwrap.dedent(setup).strip(), call=call)
        return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    return run
