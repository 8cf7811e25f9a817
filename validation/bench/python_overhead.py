"""What the Python layer costs over the C++ it calls, measured in one run.

1. attenuvis.mie.efficiencies over 1e6 spheres (x uniform in [0.1, 100],
   m = 1.33 + 1e-8i) against one C++ spheres() call over the same array
   (timed in C++ through the extension's spheres_seconds baseline), plus a
   float32 and a non-contiguous input (converted once, then the same call).
2. attenuvis.visgraph.all_to_all on classic layout 2 at 0.5 m against the
   command line `attenuvis vg layout:2 --spacing 0.5` (whole runs, wall clock:
   scene, grid, pass; the command also writes its CSV), and the pass alone.

Best of REPEAT runs each, the variants interleaved so that load from other
processes hits both alike, on THREADS threads (default 1: the overhead is per
element and per call, and one thread is what a loaded machine times most
steadily; 0 = every core).  Usage:
    PYTHONPATH=build/python /usr/bin/python3 validation/bench/python_overhead.py [ATTENUVIS_CLI] [REPEAT] [THREADS]
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import attenuvis
from attenuvis import mie, visgraph as vg

cli = sys.argv[1] if len(sys.argv) > 1 else "build/apps/attenuvis"
repeat = int(sys.argv[2]) if len(sys.argv) > 2 else 3
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 1
core = attenuvis._attenuvis.mie


def best(f):
    return min(f() for _ in range(repeat))


def timed(f):
    def run():
        t = time.perf_counter()
        f()
        return time.perf_counter() - t
    return run


x = np.random.default_rng(0).uniform(0.1, 100.0, 1_000_000)
m = 1.33 + 1e-8j
x32 = x.astype(np.float32)
x_strided = np.repeat(x, 2)[::2]
cpp, py, py32, pystrided = [], [], [], []
for _ in range(repeat):
    cpp.append(core.spheres_seconds(x, m, threads))
    py.append(timed(lambda: mie.efficiencies(x, m, threads=threads))())
    py32.append(timed(lambda: mie.efficiencies(x32, m, threads=threads))())
    pystrided.append(timed(lambda: mie.efficiencies(x_strided, m, threads=threads))())
c = min(cpp)
print(f"mie: 1e6 spheres, x in [0.1, 100], m = 1.33+1e-8i, best of {repeat}, threads {threads}")
print(f"  C++ spheres()                 {c:.3f} s")
for name, t in (("efficiencies(float64)", py), ("efficiencies(float32)", py32), ("efficiencies(strided)", pystrided)):
    print(f"  Python {name:22s} {min(t):.3f} s   ratio {min(t) / c:.3f}")

with tempfile.TemporaryDirectory() as tmp:
    out, summary = os.path.join(tmp, "s.csv"), os.path.join(tmp, "s.json")
    command = [cli, "vg", "layout:2", "--spacing", "0.5", "--conditions", "clear", "--out", out,
               "--summary", summary, "--quiet", "--threads", str(threads)]
    sigma = attenuvis.weather.sigma("clear").value
    cli_total, cli_pass, py_total, py_pass = [], [], [], []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run(command, check=True)
        cli_total.append(time.perf_counter() - t)
        with open(summary) as f:
            cli_pass.append(json.load(f)["time_s"]["visibility"])
        t = time.perf_counter()
        scene = vg.Scene.layout(2)
        eyes = vg.node_grid(scene, 0.5)
        r = vg.all_to_all(scene, eyes, [sigma], threads=threads)
        py_total.append(time.perf_counter() - t)
        py_pass.append(r.stats["seconds"])
print(f"visgraph: classic layout 2 at 0.5 m, {len(eyes)} nodes, {r.stats['pairs_total']} pairs, best of {repeat}, threads {threads}")
print(f"  command line total {min(cli_total):.3f} s, pass {min(cli_pass):.3f} s")
print(f"  Python       total {min(py_total):.3f} s, pass {min(py_pass):.3f} s")
print(f"  ratio Python / command line: total {min(py_total) / min(cli_total):.3f}, pass {min(py_pass) / min(cli_pass):.3f}")
