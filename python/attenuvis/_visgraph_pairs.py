"""All-to-all and source-to-target visibility: lines of sight weighted by contrast.

Part of attenuvis.visgraph (its public names are re-exported there)."""

from __future__ import annotations

import warnings
from typing import Callable, NamedTuple, Optional, Sequence
import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis
from ._visgraph_scene import Scene

_core = _attenuvis.visgraph


class Edges(NamedTuple):
    """Visible pairs of a pass, returned only with ``edges=True``.

    Attributes
    ----------
    i, j : numpy.ndarray of uint32
        Node indices of each pair (:func:`to_targets`: j indexes the
        targets).
    distance : numpy.ndarray of float64
        Distance between the two ends (m).

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> scene = vg.Scene.layout(2)
    >>> eyes = vg.node_grid(scene, 5.0)
    >>> e = vg.all_to_all(scene, eyes[:2], [0.0], edges=True).edges
    >>> print(e.i, e.j, e.distance)
    [0] [1] [5.]
    """

    i: np.ndarray
    j: np.ndarray
    distance: np.ndarray


class VisibilityResult(NamedTuple):
    """Scores of a visibility pass, one column per eye point.

    Returned by :func:`all_to_all` and :func:`to_targets`; N eyes (or
    sources), K extinction coefficients.

    Attributes
    ----------
    degree : numpy.ndarray of uint32, shape (N,), or None
        Visible partners; None when pruning withheld it.
    sum : numpy.ndarray of float64, shape (K, N)
        S_S, the sum over visible partners of exp(-sigma_k d).
    average : numpy.ndarray of float64, shape (K, N)
        S_A = S_S / degree (NaN where degree is 0, all NaN without degree).
    pruned : numpy.ndarray of uint32, shape (N,)
        Partners skipped by pruning.
    mean_distance, max_distance : numpy.ndarray of float64, shape (N,), or None
        Distance statistics of the visible partners (m); None unless
        ``distance_stats=True``.
    edges : Edges or None
        Every visible pair; None unless ``edges=True``.
    stats : dict
        pairs_total, pairs_cast, pairs_visible, pairs_culled_visible and
        pairs_culled_blocked (decided without rays by exact culling),
        coincident_pairs, pruning_radius (m), pruning_note (what pruning
        dropped and why, or why it was not applied: prune_below prunes only
        where that is faster than the exact pass), prune_below, seconds.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> scene = vg.Scene.layout(2)
    >>> r = vg.all_to_all(scene, vg.node_grid(scene, 5.0), [1e-3])
    >>> r.stats["pairs_total"], r.stats["pairs_visible"]
    (4560, 3405)
    """

    degree: Optional[np.ndarray]
    sum: np.ndarray
    average: np.ndarray
    pruned: np.ndarray
    mean_distance: Optional[np.ndarray]
    max_distance: Optional[np.ndarray]
    edges: Optional[Edges]
    stats: dict

    def columns(self, labels: Optional[Sequence[str]] = None) -> dict:
        """The scores as named columns, as the command line's CSV names them.

        Parameters
        ----------
        labels : sequence of str, optional
            One name per sigma (e.g. the conditions, "clear", "fog"); None
            names them 0, 1, ...

        Returns
        -------
        dict of str to numpy.ndarray
            "node", then "degree" (when exact), "sum:LABEL" and "avg:LABEL"
            (avg only with the degree) per sigma, and "mean_distance",
            "max_distance" when computed.

        Raises
        ------
        ValueError
            If ``labels`` does not have one name per sigma.

        Examples
        --------
        >>> from attenuvis import visgraph as vg
        >>> scene = vg.Scene.layout(2)
        >>> r = vg.all_to_all(scene, vg.node_grid(scene, 10.0), [0.0, 0.01])
        >>> list(r.columns(["clear", "fog"]))
        ['node', 'degree', 'sum:clear', 'avg:clear', 'sum:fog', 'avg:fog']
        """
        k = len(self.sum)
        names = [str(i) for i in range(k)] if labels is None else [str(label) for label in labels]
        if len(names) != k:
            raise ValueError(f"labels: expected one name per sigma ({k}), got {len(names)}")
        out = {"node": np.arange(self.sum.shape[1])}
        if self.degree is not None:
            out["degree"] = self.degree
        for i, name in enumerate(names):
            out[f"sum:{name}"] = self.sum[i]
            if self.degree is not None:
                out[f"avg:{name}"] = self.average[i]
        if self.mean_distance is not None:
            out["mean_distance"] = self.mean_distance
            out["max_distance"] = self.max_distance
        return out

    def to_geopandas(self, eyes: ArrayLike, crs=None, labels: Optional[Sequence[str]] = None):
        """The scores as a GeoDataFrame of 3-D points, for a GIS.

        Needs geopandas (Debian: python3-geopandas), imported only here: the
        package itself works without it.

        Parameters
        ----------
        eyes : array_like of float, shape (N, 3)
            The eye points the pass was run on (its sources for
            :func:`to_targets`).
        crs : optional
            Their CRS, anything geopandas accepts (``scene.crs``, "EPSG:28992").
        labels : sequence of str, optional
            Names of the sigmas, as :meth:`columns`.

        Returns
        -------
        geopandas.GeoDataFrame
            The columns of :meth:`columns` and a point geometry (x, y, z) per
            node.

        Raises
        ------
        ImportError
            When geopandas is not installed.
        ValueError
            If ``eyes`` does not hold one point per node.

        Examples
        --------
        >>> from attenuvis import visgraph as vg
        >>> scene = vg.Scene.layout(2)
        >>> eyes = vg.node_grid(scene, 10.0)
        >>> r = vg.all_to_all(scene, eyes, [0.0, 0.01])
        >>> try:
        ...     frame = r.to_geopandas(eyes, "EPSG:28992", labels=["clear", "fog"])
        ... except ImportError:  # geopandas is not installed
        ...     frame = None
        >>> frame is None or list(frame.columns)[:3] == ["node", "degree", "sum:clear"]
        True
        """
        try:
            import geopandas
        except ImportError as e:
            raise ImportError("to_geopandas needs geopandas (Debian: apt install python3-geopandas); "
                              "columns() gives the same scores without it") from e
        e = _eyes(eyes, "eyes")
        if len(e) != self.sum.shape[1]:
            raise ValueError(f"eyes: the result has {self.sum.shape[1]} nodes, eyes {len(e)} points")
        geometry = geopandas.points_from_xy(e[:, 0], e[:, 1], e[:, 2])
        return geopandas.GeoDataFrame(self.columns(labels), geometry=geometry, crs=crs)


def _sigmas(sigmas) -> list:
    s = np.atleast_1d(np.asarray(sigmas, dtype=np.float64))
    if s.ndim != 1:
        raise ValueError("sigmas: a number or a 1-D sequence of extinction coefficients in 1/m")
    bad = np.flatnonzero(~(np.isfinite(s) & (s >= 0)))
    if bad.size:
        raise ValueError(f"sigmas[{bad[0]}]: {s[bad[0]]} is not a finite extinction coefficient >= 0 (1/m)")
    return [float(v) for v in s]


def _result(d) -> VisibilityResult:
    degree = d["degree"]
    total = d["sum"]
    with np.errstate(invalid="ignore", divide="ignore"):
        average = total / degree if degree is not None else np.full_like(total, np.nan)
        if degree is not None:
            average[:, degree == 0] = np.nan
    edges = Edges(d["edge_i"], d["edge_j"], d["edge_distance"]) if "edge_i" in d else None
    stats = {k: d[k] for k in ("pairs_total", "pairs_cast", "pairs_visible", "coincident_pairs", "pruning_radius",
                               "pruning_note", "pairs_culled_visible", "pairs_culled_blocked", "prune_below", "seconds")}
    return VisibilityResult(degree, total, average, d["pruned"], d["mean_distance"], d["max_distance"], edges, stats)


def _eyes(a, what) -> np.ndarray:
    e = np.ascontiguousarray(a, dtype=np.float64)
    if e.ndim != 2 or e.shape[1] != 3:
        raise ValueError(f"{what}: expected an (N, 3) array of x, y, z in metres, got shape {e.shape}")
    return e


def _prune_below(prune_below: float, tolerance: Optional[float]) -> float:
    """``tolerance=`` is the former name of ``prune_below=`` (the command line's --prune-below)."""
    if tolerance is None:
        return float(prune_below)
    if prune_below:
        raise TypeError("give prune_below= only (tolerance= is its former name)")
    warnings.warn("tolerance= is deprecated: use prune_below=", DeprecationWarning, stacklevel=3)
    return float(tolerance)


def all_to_all(scene: Scene, eyes: ArrayLike, sigmas: ArrayLike, *, prune_below: float = 0.0,
               max_distance: float = np.inf, distance_stats: bool = False, threads: int = 0,
               progress: Optional[Callable[[int, int], None]] = None, edges: bool = False,
               tolerance: Optional[float] = None) -> VisibilityResult:
    """Visibility scores of every unordered pair of eye points.

    Each pair is cast once and both ends are credited.

    Parameters
    ----------
    scene : Scene
        The occluding geometry.
    eyes : array_like of float, shape (N, 3)
        Eye points (m), e.g. from :func:`node_grid`.
    sigmas : float or sequence of float
        Extinction coefficients (1/m, finite, >= 0), one row of
        ``sum``/``average`` each.
    prune_below : float, default 0
        If > 0, pairs whose exp(-sigma_min d) < prune_below may be pruned
        (then ``degree`` is None); see ``stats["pruning_note"]``.
    max_distance : float, default inf
        Farther pairs (m) are not lines of sight.
    distance_stats : bool, default False
        Also return mean_distance and max_distance per eye.
    threads : int, default 0
        Worker threads (0 = every core).  Results do not depend on it.
    progress : callable, optional
        Called about twice a second as ``progress(pairs_done, pairs_total)``
        on the calling thread; an exception it raises stops the pass.
    edges : bool, default False
        Also return every visible pair (O(visible pairs) memory; only then
        are they kept).
    tolerance : float, optional
        Deprecated former name of ``prune_below``.

    Returns
    -------
    VisibilityResult

    Raises
    ------
    ValueError
        If ``eyes`` is not (N, 3) or a sigma is negative or not finite.
    TypeError
        If both ``prune_below`` and ``tolerance`` are given.
    KeyboardInterrupt
        On Ctrl-C, which also stops the C++ pass.

    Warns
    -----
    DeprecationWarning
        When ``tolerance`` is given.

    Examples
    --------
    Behind a wall, across open ground:

    >>> import numpy as np
    >>> from attenuvis import visgraph as vg
    >>> scene = vg.Scene.from_arrays(
    ...     [[0, 0, 0], [20, 0, 0], [20, 20, 0], [0, 20, 0], [10, 0, 0], [10, 8, 0], [10, 8, 3], [10, 0, 3]],
    ...     [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    >>> eyes = [[5, 4, 1.7], [15, 4, 1.7], [15, 12, 1.7]]
    >>> r = vg.all_to_all(scene, eyes, [0.0, 0.01], edges=True)
    >>> print(r.degree)
    [0 1 1]
    >>> print(np.round(r.sum, 4))
    [[0.     1.     1.    ]
     [0.     0.9231 0.9231]]
    >>> print(r.edges.i, r.edges.j, r.edges.distance)
    [1] [2] [8.]
    """
    e = _eyes(eyes, "eyes")
    n = len(e)
    total = n * (n - 1) // 2
    cb = None if progress is None else (lambda done: progress(done, total))
    d = _core.all_to_all(scene._cpp, e, _sigmas(sigmas), _prune_below(prune_below, tolerance), float(max_distance),
                         bool(distance_stats), int(threads), bool(edges), cb)
    return _result(d)


def to_targets(scene: Scene, sources: ArrayLike, targets: ArrayLike, sigmas: ArrayLike, *, prune_below: float = 0.0,
               max_distance: float = np.inf, distance_stats: bool = False, threads: int = 0,
               progress: Optional[Callable[[int, int], None]] = None, edges: bool = False,
               tolerance: Optional[float] = None) -> VisibilityResult:
    """Visibility scores of every source against every target.

    The source is credited: the seed's single-point analysis is sources =
    all nodes, one target.

    Parameters
    ----------
    scene : Scene
        The occluding geometry.
    sources : array_like of float, shape (N, 3)
        Eye points credited (m).
    targets : array_like of float, shape (M, 3)
        Points they look at (m).
    sigmas : float or sequence of float
        Extinction coefficients (1/m).
    prune_below, max_distance, distance_stats, threads, progress, edges, tolerance
        As :func:`all_to_all`; progress counts N * M pairs.

    Returns
    -------
    VisibilityResult
        One column per source; the edges' j indexes the targets.

    Raises
    ------
    ValueError
        If ``sources`` or ``targets`` is not (N, 3), or a sigma is negative
        or not finite.
    TypeError, KeyboardInterrupt
        As :func:`all_to_all` (which also says when a DeprecationWarning
        comes).

    Examples
    --------
    >>> import numpy as np
    >>> from attenuvis import visgraph as vg
    >>> scene = vg.Scene.from_arrays(
    ...     [[0, 0, 0], [20, 0, 0], [20, 20, 0], [0, 20, 0], [10, 0, 0], [10, 8, 0], [10, 8, 3], [10, 0, 3]],
    ...     [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    >>> sources = [[5, 4, 1.7], [15, 4, 1.7], [15, 12, 1.7]]
    >>> r = vg.to_targets(scene, sources, [[5, 12, 1.7]], [0.01], edges=True)
    >>> print(r.degree, np.round(r.sum, 4))
    [1 0 1] [[0.9231 0.     0.9048]]
    >>> print(r.edges.i, r.edges.j, r.edges.distance)
    [0 2] [0 0] [ 8. 10.]
    """
    s = _eyes(sources, "sources")
    t = _eyes(targets, "targets")
    total = len(s) * len(t)
    cb = None if progress is None else (lambda done: progress(done, total))
    d = _core.to_targets(scene._cpp, s, t, _sigmas(sigmas), _prune_below(prune_below, tolerance), float(max_distance),
                         bool(distance_stats), int(threads), bool(edges), cb)
    return _result(d)
