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

Examples
--------
>>> from attenuvis import visgraph as vg
>>> scene = vg.Scene.layout(2)
>>> eyes = vg.node_grid(scene, 5.0)
>>> r = vg.all_to_all(scene, eyes, [1e-3, 2e-2])
>>> r.sum.shape
(2, 96)
"""

from __future__ import annotations

from ._visgraph_scene import Scene, classic_layout_names, node_grid
from ._visgraph_pairs import Edges, VisibilityResult, all_to_all, to_targets
from .space_syntax import KOSCHMIEDER_CONTRAST, SpaceSyntaxResult, space_syntax, space_syntax_of_graph

__all__ = ["Scene", "node_grid", "all_to_all", "to_targets", "VisibilityResult", "Edges", "classic_layout_names",
           "space_syntax", "space_syntax_of_graph", "SpaceSyntaxResult", "KOSCHMIEDER_CONTRAST"]

# The definitions live in the private modules above; they are documented,
# printed and pickled as this module's own.
for _name in ("Scene", "classic_layout_names", "node_grid", "Edges", "VisibilityResult", "all_to_all", "to_targets"):
    globals()[_name].__module__ = __name__
del _name
