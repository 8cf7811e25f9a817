"""An independent computation of the space-syntax measures with networkx
(Debian's python3-networkx), from the definitions in
visgraph/include/attenuvis/visgraph/space_syntax.hpp: networkx's BFS,
clustering (plain and Onnela-weighted), Dijkstra and components, Python sets
for controllability, and exact rational arithmetic (fractions) for the line
walk of through vision.  Used by test_space_syntax.py and by
validation/bench/space_syntax_networkx.py.
"""

from __future__ import annotations

import math
from fractions import Fraction

import networkx as nx
import numpy as np


def distances(eyes, i, j):
    """d_ij as the C++ evaluates it: sqrt(dx*dx + dy*dy + dz*dz), in float64."""
    e = np.asarray(eyes, dtype=np.float64)
    dx = e[i, 0] - e[j, 0]
    dy = e[i, 1] - e[j, 1]
    dz = e[i, 2] - e[j, 2]
    return np.sqrt(dx * dx + dy * dy + dz * dz)


def weather_graph(n, i, j, d, sigma, eps):
    """G_k: the edges whose contrast exp(-sigma d) >= eps, with d and C as attributes."""
    g = nx.Graph()
    g.add_nodes_from(range(n))
    c = np.exp(-sigma * d)
    keep = np.ones(len(d), dtype=bool) if eps <= 0 else c >= eps
    g.add_edges_from((int(a), int(b), {"d": float(dd), "c": float(cc)})
                     for a, b, dd, cc, k in zip(i, j, d, c, keep) if k)
    return g


def d_value(n):
    return 2.0 * (n * (math.log2((n + 2.0) / 3.0) - 1.0) + 1.0) / ((n - 1.0) * (n - 2.0))


def p_value(n):
    return 2.0 * (n - math.log2(n) - 1.0) / ((n - 1.0) * (n - 2.0))


def depth_measures(lengths):
    """Node count, mean depth, the integrations and entropies from the BFS depths of one origin."""
    n = len(lengths)
    td = sum(lengths.values())
    out = {"node_count": float(n), "mean_depth": -1.0, "integration_hh": -1.0, "integration_pvalue": -1.0,
           "integration_tekl": -1.0, "entropy": -1.0, "relativised_entropy": -1.0}
    if n <= 1:
        return out
    md = td / (n - 1.0)
    out["mean_depth"] = md
    if n > 2 and md > 1.0:
        ra = 2.0 * (md - 1.0) / (n - 2.0)
        out["integration_hh"] = d_value(n) / ra
        out["integration_pvalue"] = p_value(n) / ra
        if td - n + 1.0 > 1.0:
            out["integration_tekl"] = math.log(0.5 * (n - 2.0)) / math.log(td - n + 1.0)
    counts = {}
    for v in lengths.values():
        counts[v] = counts.get(v, 0) + 1
    entropy = relativised = 0.0
    for depth in sorted(counts):
        if depth == 0:
            continue
        p = counts[depth] / (n - 1.0)
        entropy -= p * math.log2(p)
        q = md ** depth / math.factorial(depth + 1) * math.exp(-md)
        relativised += p * math.log2(p / q)
    out["entropy"] = entropy
    out["relativised_entropy"] = relativised
    return out


def local_measures(g, sigma):
    """Connectivity, moments, clustering, control, controllability and the weighted local measures."""
    n = g.number_of_nodes()
    out = {k: np.zeros(n) for k in ("connectivity", "point_first_moment", "point_second_moment", "clustering",
                                    "control", "controllability", "connectivity_weighted", "first_moment_weighted",
                                    "control_weighted", "clustering_weighted")}
    clustering = nx.clustering(g)
    if g.number_of_edges():
        weighted = nx.clustering(g, weight="c")
    else:
        weighted = {v: 0.0 for v in g}
    ss = {v: sum(g[v][u]["c"] for u in g[v]) for v in g}
    for v in g:
        k = g.degree(v)
        nb = list(g[v])
        out["connectivity"][v] = k
        out["point_first_moment"][v] = sum(g[v][u]["d"] for u in nb)
        out["point_second_moment"][v] = sum(g[v][u]["d"] ** 2 for u in nb)
        out["connectivity_weighted"][v] = ss[v]
        out["first_moment_weighted"][v] = sum(g[v][u]["c"] * g[v][u]["d"] for u in nb)
        union = set()
        for u in nb:
            union |= set(g[u])
        out["clustering"][v] = clustering[v] if k > 1 else -1.0
        out["clustering_weighted"][v] = weighted[v] if k > 1 else -1.0
        out["control"][v] = sum(1.0 / g.degree(u) for u in nb) if k > 1 else -1.0
        out["control_weighted"][v] = sum(g[v][u]["c"] / ss[u] for u in nb) if k > 1 else -1.0
        out["controllability"][v] = k / len(union) if k > 1 else -1.0
    return out


def global_measures(g, radius=0):
    names = ("node_count", "mean_depth", "integration_hh", "integration_pvalue", "integration_tekl", "entropy",
             "relativised_entropy")
    out = {k: np.zeros(g.number_of_nodes()) for k in names}
    for v in g:
        lengths = nx.single_source_shortest_path_length(g, v, cutoff=radius if radius > 0 else None)
        for k, value in depth_measures(lengths).items():
            out[k][v] = value
    return out


def metric_measures(g, full, sigma):
    """metric_mean_distance on g (sum over reached nodes / their count, the origin included) and
    weather_reach on the full graph."""
    n = g.number_of_nodes()
    mean, reach = np.zeros(n), np.zeros(n)
    for v in g:
        lengths = nx.single_source_dijkstra_path_length(g, v, weight="d")
        mean[v] = sum(lengths.values()) / len(lengths)
        full_lengths = nx.single_source_dijkstra_path_length(full, v, weight="d")
        reach[v] = sum(math.exp(-sigma * length) for u, length in full_lengths.items() if u != v)
    return {"metric_mean_distance": mean, "weather_reach": reach}


def component_sizes(g):
    size = np.zeros(g.number_of_nodes())
    for component in nx.connected_components(g):
        for v in component:
            size[v] = len(component)
    return size


def step_depths(g, origins):
    depth = np.full(g.number_of_nodes(), -1.0)
    for v, length in nx.multi_source_dijkstra_path_length(g, set(origins), weight=lambda a, b, e: 1).items():
        depth[v] = length
    return depth


def line_cells(a, b):
    """Cells strictly between cells a and b on depthmapX's line walk: one per step along the major
    axis from centre to centre, two where the minor coordinate meets a cell boundary (exact fractions)."""
    (ax, ay), (bx, by) = a, b
    dx, dy = bx - ax, by - ay
    t = max(abs(dx), abs(dy))
    cells = []
    for s in range(1, t):
        x = Fraction(2 * ax + 1, 2) + Fraction(s * dx, t)
        y = Fraction(2 * ay + 1, 2) + Fraction(s * dy, t)
        if abs(dx) == abs(dy):
            cells.append((math.floor(x), math.floor(y)))
        elif abs(dx) > abs(dy):
            cells += [(math.floor(x), y - 1), (math.floor(x), y)] if y.denominator == 1 else [(math.floor(x), math.floor(y))]
        else:
            cells += [(x - 1, math.floor(y)), (x, math.floor(y))] if x.denominator == 1 else [(math.floor(x), math.floor(y))]
    return [(int(cx), int(cy)) for cx, cy in cells]


def through_vision(g, eyes, spacing):
    e = np.asarray(eyes, dtype=np.float64)
    x0, y0 = e[:, 0].min(), e[:, 1].min()
    cell = [(int(round((p[0] - x0) / spacing)), int(round((p[1] - y0) / spacing))) for p in e]
    at = {}
    for v, c in enumerate(cell):
        at.setdefault(c, []).append(v)
    count, weighted = np.zeros(len(e)), np.zeros(len(e))
    for a, b, data in g.edges(data=True):
        for c in line_cells(cell[a], cell[b]):
            for v in at.get(c, []):
                count[v] += 1
                weighted[v] += data["c"]
    return {"through_vision": count, "through_vision_weighted": weighted}
