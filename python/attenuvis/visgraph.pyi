from typing import Callable, List, NamedTuple, Optional, Sequence
import numpy as np
from numpy.typing import ArrayLike

class Scene:
    @classmethod
    def from_file(cls, path: str, *, up_axis: str = ..., lod: str = ...) -> Scene: ...
    @classmethod
    def from_obj(cls, path: str, *, up_axis: str = ...) -> Scene: ...
    @classmethod
    def layout(cls, index: int) -> Scene: ...
    @classmethod
    def city(cls, seed: Optional[int] = ...) -> Scene: ...
    @classmethod
    def from_arrays(cls, vertices: ArrayLike, triangles: ArrayLike, groups: Optional[Sequence[str]] = ...) -> Scene: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def bounds(self) -> np.ndarray: ...
    @property
    def groups(self) -> List[str]: ...
    @property
    def warnings(self) -> List[str]: ...

class Edges(NamedTuple):
    i: np.ndarray
    j: np.ndarray
    distance: np.ndarray

class VisibilityResult(NamedTuple):
    degree: Optional[np.ndarray]
    sum: np.ndarray
    average: np.ndarray
    pruned: np.ndarray
    mean_distance: Optional[np.ndarray]
    max_distance: Optional[np.ndarray]
    edges: Optional[Edges]
    stats: dict

def classic_layout_names() -> List[str]: ...
def node_grid(scene: Scene, spacing: float, *, walkable: Optional[Sequence[str]] = ..., eye_height: float = ...,
              max_slope_deg: float = ...) -> np.ndarray: ...
def all_to_all(scene: Scene, eyes: ArrayLike, sigmas: ArrayLike, *, prune_below: float = ..., max_distance: float = ...,
               distance_stats: bool = ..., threads: int = ..., progress: Optional[Callable[[int, int], None]] = ...,
               edges: bool = ..., tolerance: Optional[float] = ...) -> VisibilityResult: ...
def to_targets(scene: Scene, sources: ArrayLike, targets: ArrayLike, sigmas: ArrayLike, *, prune_below: float = ...,
               max_distance: float = ..., distance_stats: bool = ..., threads: int = ...,
               progress: Optional[Callable[[int, int], None]] = ..., edges: bool = ...,
               tolerance: Optional[float] = ...) -> VisibilityResult: ...
