#!/usr/bin/python3
"""The five classic layouts at 1 m: clustering, control, mean depth and
integration [HH] of attenuvis against networkx on attenuvis's own edge list.

networkx needs about a second per node on these dense graphs (2,000-2,460
nodes, 0.9-2.2 million lines of sight) for clustering and for a BFS, so the
whole comparison takes hours on two cores.  --sample K compares K nodes per
layout, evenly spaced in node order (control is compared at every node: it
only needs the degrees); without it every node is compared.  The ctest suite
(python/tests/test_space_syntax.py) runs the same comparison on the layouts
at 5 m and on random graphs.

Usage (from the build tree, with the package importable):
    PYTHONPATH=build/python /usr/bin/python3 validation/bench/space_syntax_networkx.py [--sample K] [--spacing 1]
"""

import argparse
import os
import sys
import time

import networkx as nx
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python", "tests"))
import space_syntax_reference as ref  # noqa: E402

from attenuvis import visgraph as vg  # noqa: E402


def compare_layout(index, spacing, sample):
    scene = vg.Scene.layout(index)
    eyes = vg.node_grid(scene, spacing)
    t0 = time.time()
    r = vg.space_syntax(scene, eyes, [0.0], measures="clustering,control,mean-depth,integration", threshold=0)
    ours = time.time() - t0
    e = vg.all_to_all(scene, eyes, [0.0], edges=True).edges
    g = nx.Graph()
    g.add_nodes_from(range(len(eyes)))
    g.add_edges_from(zip(e.i.tolist(), e.j.tolist()))
    n = len(eyes)
    nodes = list(range(n)) if not sample else sorted(set(np.linspace(0, n - 1, sample).astype(int).tolist()))
    t1 = time.time()
    control = np.array([sum(1.0 / g.degree(u) for u in g[v]) if g.degree(v) > 1 else -1.0 for v in range(n)])
    clustering = nx.clustering(g, nodes=nodes)
    worst = {"clustering": 0.0, "control": float(np.max(np.abs(control - r["control"][0]) / np.abs(control))),
             "mean_depth": 0.0, "integration_hh": 0.0}
    depth_equal = 0
    for v in nodes:
        c = clustering[v] if g.degree(v) > 1 else -1.0
        worst["clustering"] = max(worst["clustering"], abs(c - r["clustering"][0][v]) / max(abs(c), 1e-300))
        d = ref.depth_measures(nx.single_source_shortest_path_length(g, v))
        depth_equal += d["mean_depth"] == r["mean_depth"][0][v]
        for k in ("mean_depth", "integration_hh"):
            worst[k] = max(worst[k], abs(d[k] - r[k][0][v]) / abs(d[k]))
    theirs = time.time() - t1
    print(f"layout {index}: {n} nodes, {len(e.i)} lines; compared {len(nodes)} nodes "
          f"(control at all {n}); mean depth equal at {depth_equal}/{len(nodes)}; largest relative differences: "
          + ", ".join(f"{k} {v:.1e}" for k, v in worst.items())
          + f"; attenuvis {ours:.2f} s (pass and measures, every node), networkx {theirs:.0f} s", flush=True)
    return all(v <= 1e-12 for v in worst.values()) and depth_equal == len(nodes)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sample", type=int, default=0, help="nodes per layout (0: every node)")
    parser.add_argument("--spacing", type=float, default=1.0)
    a = parser.parse_args()
    ok = all([compare_layout(k, a.spacing, a.sample) for k in range(5)])
    print("all equal to 1e-12" if ok else "DIFFERENCES ABOVE 1e-12")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
