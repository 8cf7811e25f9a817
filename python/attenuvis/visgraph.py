"""Weather-weighted visibility graphs over 3D scenes (attenuvis::visgraph,
Embree).

Coordinates in metres, z up.  For every eye point and every extinction
coefficient sigma_k (1/m) a pass reports

* ``degree``: how many other eyes it sees,
* ``sum[k]``: S_S = sum over visible partners of exp(-sigma_k d) (the seed
  paper's sum score),
* ``average[k]``: S_A = S_S / degree (NaN where degree is 0),
* ``pruned``: partners skipped by pruning (``prune_below > 0``), each worth at
  most ``prune_below`` in S_S,

and, only when asked (``edges=True``), every visible pair as arrays (i, j,
distance).  Results do not depend on the thread count (fixed-point sums,
visgraph/visibility.hpp).  Long passes release the GIL; Ctrl-C raises
KeyboardInterrupt within a fraction of a second and stops the C++ work.
"""

from __future__ import annotations

import warnings
from typing import Callable, NamedTuple, Optional, Sequence

import numpy as np

from . import _attenuvis

_core = _attenuvis.visgraph

__all__ = ["Scene", "node_grid", "all_to_all", "to_targets", "VisibilityResult", "Edges", "classic_layout_names"]


class Scene:
    """A ray-traceable triangle scene (Embree BVH, built once)."""

    def __init__(self, cpp):
        self._cpp = cpp

    @classmethod
    def from_file(cls, path, *, up_axis: str = "z", lod: str = "") -> "Scene":
        """OBJ, CityJSON (.json/.city.json/.jsonl) or glTF (.gltf/.glb), recognised by content.
        ``up_axis`` ("z" or "y") applies to OBJ; ``lod`` picks a CityJSON level of detail."""
        return cls(_core.Scene.from_file(str(path), up_axis, lod))

    @classmethod
    def from_obj(cls, path, *, up_axis: str = "z") -> "Scene":
        """A Wavefront OBJ file; groups (``g``) name the surfaces."""
        return cls.from_file(path, up_axis=up_axis)

    @classmethod
    def layout(cls, index: int) -> "Scene":
        """One of the five classic 50 x 50 m layouts of the seed paper (0..4);
        nodes stand on its floor by default."""
        return cls(_core.Scene.from_spec(f"layout:{int(index)}"))

    @classmethod
    def city(cls, seed: Optional[int] = None) -> "Scene":
        """The synthetic city; nodes stand on sidewalks and crosswalks by default."""
        return cls(_core.Scene.from_spec("city" if seed is None else f"city:{int(seed)}"))

    @classmethod
    def from_arrays(cls, vertices, triangles, groups=None) -> "Scene":
        """A scene from an (V, 3) float array of vertices (m) and an (T, 3)
        integer array of vertex indices.  ``groups``: None (one group
        "default"), or a length-T sequence of group names (str) per triangle."""
        v = np.ascontiguousarray(vertices, dtype=np.float64)
        t = np.asarray(triangles)
        if t.ndim != 2 or t.shape[1:] != (3,):
            raise ValueError(f"triangles: expected an (M, 3) array of vertex indices, got shape {t.shape}")
        if t.dtype.kind not in "iu":
            raise TypeError(f"triangles must be integers, got dtype {t.dtype}")
        if t.size and (t.min() < 0 or t.max() >= len(v)):
            bad = int(np.argmax((t < 0).any(axis=1) | (t >= len(v)).any(axis=1)))
            raise ValueError(f"triangle {bad}: vertex index out of range ({len(v)} vertices)")
        if groups is None:
            names, index = ["default"], np.zeros(len(t), dtype=np.uint32)
        else:
            g = np.asarray(groups)
            if g.shape != (len(t),):
                raise ValueError(f"groups: expected one name per triangle ({len(t)}), got shape {g.shape}")
            names, index = np.unique(g.astype(str), return_inverse=True)
            names = list(names)
        return cls(_core.Scene.from_arrays(v, np.ascontiguousarray(t, dtype=np.uint32),
                                           np.ascontiguousarray(index, dtype=np.uint32), names))

    @property
    def triangle_count(self) -> int:
        """Number of triangles in the BVH."""
        return self._cpp.triangle_count

    @property
    def bounds(self) -> np.ndarray:
        """(2, 3) array: min and max corner (m)."""
        return self._cpp.bounds

    @property
    def groups(self) -> Sequence[str]:
        """Group names (OBJ ``g``/``o``, or materials), what ``walkable=`` selects."""
        return self._cpp.groups

    @property
    def warnings(self) -> Sequence[str]:
        """What the reader noticed (an up axis that looks wrong, faces skipped)."""
        return self._cpp.warnings

    def __repr__(self) -> str:
        return f"Scene({self._cpp.format}, {self.triangle_count} triangles, groups={list(self.groups)})"


def classic_layout_names():
    """Names of the classic layouts 0..4."""
    return [_core.classic_layout_name(i) for i in range(5)]


def node_grid(scene: Scene, spacing: float, *, walkable: Optional[Sequence[str]] = None, eye_height: float = 1.7,
              max_slope_deg: float = 90.0) -> np.ndarray:
    """Eye points on a square grid of pitch ``spacing`` (m) over the scene,
    ``eye_height`` (m) above the surface people stand on: the named
    ``walkable`` groups (or classes; "*" = any surface), else the scene's own
    rule (shipped scenes: their floors and sidewalks; files: the lowest
    surface outside every solid, visgraph/nodes.hpp).  Returns an (N, 3)
    float64 array."""
    return _core.node_grid(scene._cpp, float(spacing), None if walkable is None else list(walkable),
                           float(eye_height), float(max_slope_deg))


class Edges(NamedTuple):
    """Visible pairs: node indices i, j (uint32; to_targets: j indexes the
    targets) and distance (m)."""

    i: np.ndarray
    j: np.ndarray
    distance: np.ndarray


class VisibilityResult(NamedTuple):
    """degree (N,) uint32 or None when pruning withheld it; sum, average
    (K, N) float64; pruned (N,) uint32; mean_distance, max_distance (N,) or
    None unless distance_stats; edges (Edges) or None unless edges=True;
    stats: pairs_total/cast/visible, pairs_culled_visible/blocked (decided
    without rays by exact culling), coincident_pairs, pruning_radius (m),
    pruning_note (what pruning dropped and why, or why it was not applied:
    prune_below prunes only where that is faster than the exact pass),
    prune_below, seconds."""

    degree: Optional[np.ndarray]
    sum: np.ndarray
    average: np.ndarray
    pruned: np.ndarray
    mean_distance: Optional[np.ndarray]
    max_distance: Optional[np.ndarray]
    edges: Optional[Edges]
    stats: dict


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


def all_to_all(scene: Scene, eyes, sigmas, *, prune_below: float = 0.0, max_distance: float = np.inf,
               distance_stats: bool = False, threads: int = 0,
               progress: Optional[Callable[[int, int], None]] = None, edges: bool = False,
               tolerance: Optional[float] = None) -> VisibilityResult:
    """Every unordered pair of ``eyes`` ((N, 3), m) once, both ends credited.

    sigmas: extinction coefficients (1/m), one row of ``sum``/``average``
    each.  prune_below > 0 prunes pairs whose exp(-sigma_min d) < prune_below
    (degree then None; ``tolerance=`` is its deprecated former name).
    max_distance (m): farther pairs are not lines of sight.  threads: 0 = every core.  progress: called about twice a second
    as progress(pairs_done, pairs_total), on the calling thread; an exception
    it raises stops the pass.  edges=True also returns every visible pair
    (O(visible pairs) memory; only then are they kept).
    """
    e = _eyes(eyes, "eyes")
    n = len(e)
    total = n * (n - 1) // 2
    cb = None if progress is None else (lambda done: progress(done, total))
    d = _core.all_to_all(scene._cpp, e, _sigmas(sigmas), _prune_below(prune_below, tolerance), float(max_distance),
                         bool(distance_stats), int(threads), bool(edges), cb)
    return _result(d)


def to_targets(scene: Scene, sources, targets, sigmas, *, prune_below: float = 0.0, max_distance: float = np.inf,
               distance_stats: bool = False, threads: int = 0,
               progress: Optional[Callable[[int, int], None]] = None, edges: bool = False,
               tolerance: Optional[float] = None) -> VisibilityResult:
    """Every source against every target, the source credited (the seed's
    single-point analysis: sources = all nodes, one target).  Arguments and
    result as all_to_all; edges' j indexes the targets."""
    s = _eyes(sources, "sources")
    t = _eyes(targets, "targets")
    total = len(s) * len(t)
    cb = None if progress is None else (lambda done: progress(done, total))
    d = _core.to_targets(scene._cpp, s, t, _sigmas(sigmas), _prune_below(prune_below, tolerance), float(max_distance),
                         bool(distance_stats), int(threads), bool(edges), cb)
    return _result(d)
