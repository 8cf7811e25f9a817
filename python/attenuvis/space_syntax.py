"""Space syntax in weather: the visibility-graph-analysis (VGA) measures of
depthmapX, exact, on the lines of sight that a contrast threshold leaves in
each weather, and weighted by contrast.

Use it as ``attenuvis.visgraph.space_syntax`` (a scene and its eyes) or
``attenuvis.visgraph.space_syntax_of_graph`` (any graph given as an edge
list).  The definitions, with their sources and where they follow depthmapX,
are in the C++ header visgraph/include/attenuvis/visgraph/space_syntax.hpp
and in the guide (docs/guide/space-syntax.md).

Measures (``measures=``) and the arrays they add, each of shape (K, N), one
row per sigma:

=====================  =====================================================
connectivity           connectivity, point_first_moment, point_second_moment,
                       connectivity_weighted, first_moment_weighted
clustering             clustering
clustering-weighted    clustering_weighted
control                control, control_weighted
controllability        controllability
mean-depth             mean_depth, node_count
integration            integration_hh, integration_pvalue, integration_tekl
entropy                entropy, relativised_entropy
through-vision         through_vision, through_vision_weighted
metric                 metric_mean_distance, weather_reach
component              component_size
step-depth             step_depth (needs ``origins``)
=====================  =====================================================

With ``radius=K`` the global ones (mean depth, node count, integration,
entropy) are named with ``_rK``, e.g. ``integration_hh_r3``.
"""

from __future__ import annotations

from typing import Callable, Dict, NamedTuple, Optional, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis

# visgraph imports this module after its own helpers are defined.
from ._visgraph_pairs import _eyes, _sigmas

_core = _attenuvis.visgraph

__all__ = ["SpaceSyntaxResult", "space_syntax", "space_syntax_of_graph", "KOSCHMIEDER_CONTRAST"]

#: Koschmieder's threshold of contrast detection, the default ``threshold``.
KOSCHMIEDER_CONTRAST = 0.02


class SpaceSyntaxResult(NamedTuple):
    """Measures per node, one row per sigma.

    Attributes
    ----------
    measures : dict of str to numpy.ndarray of float64, shape (K, N)
        Each measure's values (names as in the module docstring), -1 where
        depthmapX writes -1 (e.g. clustering of a node with one neighbour).
    lines : list of int
        Lines of sight kept by the threshold in each weather's graph.
    components : list of int
        Connected components of each weather's graph.
    same_graph_as : list of int
        For each sigma, an earlier sigma whose graph is the same, or -1.
    degree : numpy.ndarray of uint32 or None
        The pass's degree (every line of sight), from :func:`space_syntax`.
    stats : dict
        bit_rows (how the graph was held), graph_bytes, seconds (the
        measures), and from :func:`space_syntax` pass_seconds, pairs_visible.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> r = vg.space_syntax_of_graph([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [0, 1], [1, 2], [0.0],
    ...                              measures="connectivity,mean-depth")
    >>> r["connectivity"], r["mean_depth"]
    (array([[1., 2., 1.]]), array([[1.5, 1. , 1.5]]))
    """

    measures: Dict[str, np.ndarray]
    lines: list
    components: list
    same_graph_as: list
    degree: Optional[np.ndarray]
    stats: dict

    def __getitem__(self, key):  # type: ignore[override]
        """``result["integration_hh"]`` is ``result.measures["integration_hh"]``."""
        if isinstance(key, str):
            return self.measures[key]
        return tuple.__getitem__(self, key)


def _measure_list(measures: Union[str, Sequence[str], None], spacing: Optional[float]) -> str:
    if measures is None:
        names = ["connectivity", "clustering", "control", "controllability", "mean-depth", "integration",
                 "entropy", "metric", "component"]
        if spacing is not None:
            names.append("through-vision")
        return ",".join(names)
    names = measures.split(",") if isinstance(measures, str) else list(measures)
    if spacing is None and ("through-vision" in names or "all" in names):
        raise ValueError("through-vision needs spacing=, the eyes' grid spacing (m): it walks the grid's cells")
    return ",".join(names)


def _radius(radius: Union[int, str]) -> int:
    if isinstance(radius, str):
        if radius != "n":
            raise ValueError(f"radius: 'n' or a positive number of steps, got {radius!r}")
        return 0
    if int(radius) != radius or radius < 0:
        raise ValueError(f"radius: 'n' (or 0) or a positive whole number of steps, got {radius!r}")
    return int(radius)


def _result(d, degree=None) -> SpaceSyntaxResult:
    stats = {k: d[k] for k in ("bit_rows", "graph_bytes", "seconds") if k in d}
    for k in ("pass_seconds", "pairs_visible"):
        if k in d:
            stats[k] = d[k]
    return SpaceSyntaxResult(dict(d["measures"]), list(d["lines"]), list(d["components"]), list(d["same_graph_as"]),
                             degree, stats)


def space_syntax(scene, eyes: ArrayLike, sigmas: ArrayLike, *, measures: Union[str, Sequence[str], None] = None,
                 radius: Union[int, str] = "n", threshold: float = KOSCHMIEDER_CONTRAST,
                 spacing: Optional[float] = None, origins: Optional[Sequence[int]] = None, threads: int = 0,
                 graph: str = "auto", progress: Optional[Callable[[int, int], None]] = None) -> SpaceSyntaxResult:
    """The space-syntax measures of the eyes' visibility graph in each weather.

    Runs the exact visibility pass (every pair of eyes) and computes the
    measures on each sigma's graph: the lines of sight whose contrast
    exp(-sigma d) is at least ``threshold``.

    Parameters
    ----------
    scene : Scene
        The occluding geometry.
    eyes : array_like of float, shape (N, 3)
        Eye points (m), e.g. from :func:`node_grid`.
    sigmas : float or sequence of float
        Extinction coefficients (1/m, finite, >= 0), one graph and one row of
        every measure each.
    measures : str or sequence of str, optional
        Names from the module docstring, comma-separated or as a list, or
        "all".  Default: every measure but clustering-weighted and
        step-depth (and through-vision unless ``spacing`` is given).
    radius : int or "n", default "n"
        Steps for the global measures (mean depth, integration, entropy).
    threshold : float, default 0.02
        Contrast threshold eps in [0, 1) (Koschmieder's 0.02); 0 keeps
        every line of sight.
    spacing : float, optional
        The eyes' grid spacing (m), which through vision needs.
    origins : sequence of int, optional
        Eye indices for step-depth.
    threads : int, default 0
        Worker threads (0 = every core).  Results do not depend on it.
    graph : {"auto", "bit-rows", "csr"}, default "auto"
        How the lines of sight are held (N x N bits, or sorted neighbour
        lists); "auto" takes the smaller.  Results do not depend on it.
    progress : callable, optional
        ``progress(pairs_done, pairs_total)`` during the pass.

    Returns
    -------
    SpaceSyntaxResult

    Raises
    ------
    ValueError
        For an unknown measure, a threshold outside [0, 1), a bad radius,
        through vision without ``spacing`` or step depth without origins.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> scene = vg.Scene.layout(2)
    >>> eyes = vg.node_grid(scene, 5.0)
    >>> r = vg.space_syntax(scene, eyes, [1.5e-4, 2.9e-2], measures="integration,clustering", threshold=0.5)
    >>> r["integration_hh"].shape, r.lines
    ((2, 96), [3405, 1756])
    """
    e = _eyes(eyes, "eyes")
    total = len(e) * (len(e) - 1) // 2
    cb = None if progress is None else (lambda done: progress(done, total))
    d = _core.space_syntax(scene._cpp, e, _sigmas(sigmas), _measure_list(measures, spacing), _radius(radius),
                           float(threshold), 0.0 if spacing is None else float(spacing),
                           [] if origins is None else [int(o) for o in origins], int(threads), str(graph), cb)
    return _result(d, d["degree"])


def space_syntax_of_graph(eyes: ArrayLike, i: ArrayLike, j: ArrayLike, sigmas: ArrayLike, *,
                          measures: Union[str, Sequence[str], None] = None, radius: Union[int, str] = "n",
                          threshold: float = KOSCHMIEDER_CONTRAST, spacing: Optional[float] = None,
                          origins: Optional[Sequence[int]] = None, threads: int = 0,
                          graph: str = "auto") -> SpaceSyntaxResult:
    """The space-syntax measures of any graph given by its edges.

    The graph of nodes ``eyes`` with an edge (i[k], j[k]) for each k (each
    pair once, i != j); distances are ``|eyes[i] - eyes[j]|``.  Otherwise as
    :func:`space_syntax`, e.g. for an edge list written by ``attenuvis vg
    --edges`` or a graph from another program.

    Parameters
    ----------
    eyes : array_like of float, shape (N, 3)
        Node positions (m); the distances d are taken from them.
    i, j : array_like of int
        The edges' ends (indices into ``eyes``).
    sigmas, measures, radius, threshold, spacing, origins, threads, graph
        As :func:`space_syntax`.

    Returns
    -------
    SpaceSyntaxResult
        Without ``degree`` (there is no pass).

    Raises
    ------
    ValueError
        As :func:`space_syntax`, and for an edge given twice or joining a
        node to itself.

    Examples
    --------
    A path of four nodes, 1 m apart:

    >>> from attenuvis import visgraph as vg
    >>> eyes = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]
    >>> r = vg.space_syntax_of_graph(eyes, [0, 1, 2], [1, 2, 3], [0.0], measures="control,mean-depth")
    >>> print(r["control"], r["mean_depth"])
    [[-1.  1.5  1.5 -1. ]] [[2.         1.33333333 1.33333333 2.        ]]
    """
    ii = np.ascontiguousarray(i, dtype=np.uint32)
    jj = np.ascontiguousarray(j, dtype=np.uint32)
    d = _core.space_syntax_edges(_eyes(eyes, "eyes"), ii, jj, _sigmas(sigmas), _measure_list(measures, spacing),
                                 _radius(radius), float(threshold), 0.0 if spacing is None else float(spacing),
                                 [] if origins is None else [int(o) for o in origins], int(threads), str(graph))
    return _result(d)
