"""Scenes (city models, layouts, ground) and the nodes where people stand.

Part of attenuvis.visgraph (its public names are re-exported there)."""

from __future__ import annotations

import os
from typing import List, Optional, Sequence, Union
import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis

_core = _attenuvis.visgraph


class Scene:
    """A ray-traceable triangle scene (Embree BVH, built once).

    Build one with :meth:`from_file`, :meth:`from_obj`, :meth:`layout`,
    :meth:`city` or :meth:`from_arrays`; the constructor wraps the
    extension's scene and is not for direct use.  Its properties
    ``triangle_count``, ``bounds``, ``groups`` and ``warnings`` describe it.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> vg.Scene.layout(2)
    Scene(layout:2, 14 triangles, groups=['floor', 'obstacle'])
    """

    def __init__(self, cpp):
        self._cpp = cpp

    @classmethod
    def from_file(cls, path: Union[str, os.PathLike], *, up_axis: str = "z", lod: str = "",
                  terrain: Union[None, str, os.PathLike] = None) -> Scene:
        """A scene from an OBJ, CityJSON or glTF file, recognised by content.

        Parameters
        ----------
        path : str or path-like
            Wavefront OBJ, CityJSON (.json/.city.json/.jsonl) or glTF
            (.gltf/.glb).
        up_axis : {"z", "y"}, default "z"
            The file's up axis; applies to OBJ (the scene is z up).
        lod : str, default ""
            CityJSON level of detail to read ("" = the reader's choice).
        terrain : None, "infer" or str or path-like, default None
            Ground to add: a DEM (a GeoTIFF or any raster GDAL reads, in the
            model's CRS, covering it; its surface joins the scene and nodes
            stand on it), ``"infer"`` for a model published as buildings
            only (a plane at its lowest z where the building bases agree
            within 0.5 m, else the Delaunay TIN of the bases, as the command
            line's default), or None for the file as it is.  :attr:`ground`
            says what was added.

        Returns
        -------
        Scene

        Raises
        ------
        RuntimeError
            If the file cannot be read or parsed (the message names the
            file and where).
        ValueError
            For a bad argument: an ``up_axis`` other than "z" or "y", a
            ``lod`` for a file that is not CityJSON, a DEM in another CRS,
            short of the model or without data where nodes would stand.

        Examples
        --------
        A ground square with a wall across it, written as OBJ:

        >>> import os, tempfile
        >>> from attenuvis import visgraph as vg
        >>> tmp = tempfile.TemporaryDirectory()
        >>> path = os.path.join(tmp.name, "wall.obj")
        >>> with open(path, "w") as f:
        ...     _ = f.write("g ground\\nv 0 0 0\\nv 20 0 0\\nv 20 20 0\\nv 0 20 0\\nf 1 2 3\\nf 1 3 4\\n"
        ...                 "g wall\\nv 10 0 0\\nv 10 8 0\\nv 10 8 3\\nv 10 0 3\\nf 5 6 7\\nf 5 7 8\\n")
        >>> vg.Scene.from_file(path)
        Scene(OBJ, 4 triangles, groups=['ground', 'wall'])
        >>> tmp.cleanup()
        """
        return cls(_core.Scene.from_file(str(path), up_axis, lod, _terrain(terrain)))

    @classmethod
    def from_footprints(cls, path: Union[str, os.PathLike], *, height_field: Optional[str] = None,
                        levels_field: Optional[str] = None, storey_height: float = 3.0,
                        terrain: Union[None, str, os.PathLike] = None, strict: bool = False,
                        base_z: float = 0.0) -> Scene:
        """Buildings extruded from a GIS layer of footprints.

        Each polygon of the file's first layer (GeoPackage, Shapefile,
        GeoJSON: any vector layer GDAL reads, in a projected CRS in metres)
        becomes a flat-roofed prism, holes and multipolygons included, its
        height from ``height_field`` or else ``levels_field`` times
        ``storey_height`` (OpenStreetMap's building:levels), standing on the
        lowest ground under its corners.

        Parameters
        ----------
        path : str or path-like
            The layer's file.
        height_field : str, optional
            Field holding each building's height (m; a number, or text such
            as "12 m").
        levels_field : str, optional
            Field holding its storeys, used where the height is missing.
        storey_height : float, default 3.0
            Metres per storey.
        terrain : None, "infer" or str or path-like, default None
            A DEM the buildings and nodes stand on (as :meth:`from_file`);
            "infer" for footprints with z; None: the plane ``base_z``.
        strict : bool, default False
            A feature without a usable height raises instead of being
            skipped (skipped ones are counted in :attr:`warnings`).
        base_z : float, default 0.0
            Height (m) of the plane footprints without z stand on when there
            is no DEM.

        Returns
        -------
        Scene
            Groups are the features' ids; classes GroundSurface,
            WallSurface, RoofSurface (and DEMTerrain).

        Raises
        ------
        ValueError
            For a layer in degrees (the message names a UTM zone to
            reproject to), geometry that is not a polygon, an empty layer, a
            self-intersecting ring or a missing field (each naming the
            feature), and the DEM refusals of :meth:`from_file`.
        RuntimeError
            If GDAL cannot read the file.

        Examples
        --------
        >>> import os, tempfile
        >>> from attenuvis import visgraph as vg
        >>> tmp = tempfile.TemporaryDirectory()
        >>> path = os.path.join(tmp.name, "houses.geojson")
        >>> with open(path, "w") as f:
        ...     _ = f.write('{"type": "FeatureCollection", "crs": {"type": "name", "properties": '
        ...                 '{"name": "urn:ogc:def:crs:EPSG::32632"}}, "features": ['
        ...                 '{"type": "Feature", "properties": {"height": 9.5}, "geometry": {"type": "Polygon", '
        ...                 '"coordinates": [[[500000, 5000000], [500010, 5000000], [500010, 5000010], '
        ...                 '[500000, 5000010], [500000, 5000000]]]}}]}')
        >>> scene = vg.Scene.from_footprints(path, height_field="height")
        >>> scene.crs, scene.triangle_count, float(scene.bounds[1, 2])
        ('EPSG:32632', 12, 9.5)
        >>> tmp.cleanup()
        """
        if not height_field and not levels_field:
            raise ValueError("from_footprints: give height_field, levels_field or both")
        return cls(_core.Scene.from_footprints(str(path), height_field or "", levels_field or "",
                                               float(storey_height), _terrain(terrain), bool(strict), float(base_z)))

    @classmethod
    def from_obj(cls, path: Union[str, os.PathLike], *, up_axis: str = "z") -> Scene:
        """A scene from a Wavefront OBJ file; groups (``g``) name the surfaces.

        Parameters
        ----------
        path : str or path-like
            The OBJ file.
        up_axis : {"z", "y"}, default "z"
            As :meth:`from_file`.

        Returns
        -------
        Scene

        Raises
        ------
        RuntimeError, ValueError
            As :meth:`from_file`.

        Examples
        --------
        >>> import pathlib, tempfile
        >>> from attenuvis import visgraph as vg
        >>> tmp = tempfile.TemporaryDirectory()
        >>> path = pathlib.Path(tmp.name) / "floor.obj"
        >>> _ = path.write_text("g floor\\nv 0 0 0\\nv 10 0 0\\nv 10 10 0\\nv 0 10 0\\nf 1 2 3\\nf 1 3 4\\n")
        >>> vg.Scene.from_obj(path).groups
        ['floor']
        >>> tmp.cleanup()
        """
        return cls.from_file(path, up_axis=up_axis)

    @classmethod
    def layout(cls, index: int) -> Scene:
        """One of the five classic 50 x 50 m layouts of the seed paper.

        Nodes stand on its floor by default.

        Parameters
        ----------
        index : int
            0..4 (names: :func:`classic_layout_names`).

        Returns
        -------
        Scene

        Raises
        ------
        ValueError
            For an index outside 0..4.

        Examples
        --------
        >>> from attenuvis import visgraph as vg
        >>> scene = vg.Scene.layout(2)
        >>> scene.triangle_count
        14
        >>> print(scene.bounds)
        [[ 0.  0.  0.]
         [50. 50. 10.]]
        """
        return cls(_core.Scene.from_spec(f"layout:{int(index)}"))

    @classmethod
    def city(cls, seed: Optional[int] = None) -> Scene:
        """The synthetic city; nodes stand on sidewalks and crosswalks by default.

        Parameters
        ----------
        seed : int, optional
            Seed of the generated city (None: the default city, as the
            command line's ``city``; a seed gives ``city:SEED``).

        Returns
        -------
        Scene

        Examples
        --------
        >>> from attenuvis import visgraph as vg
        >>> vg.Scene.city().groups
        ['sidewalk', 'crosswalk', 'road', 'ground', 'building', 'terrain']
        """
        return cls(_core.Scene.from_spec("city" if seed is None else f"city:{int(seed)}"))

    @classmethod
    def from_arrays(cls, vertices: ArrayLike, triangles: ArrayLike, groups: Optional[Sequence[str]] = None) -> Scene:
        """A scene from arrays of vertices and triangles.

        Parameters
        ----------
        vertices : array_like of float, shape (V, 3)
            Vertex coordinates (m), z up.
        triangles : array_like of int, shape (T, 3)
            Vertex indices (0-based) of each triangle.
        groups : sequence of str, optional
            One group name per triangle (length T); None puts every triangle
            in one group "default".

        Returns
        -------
        Scene

        Raises
        ------
        ValueError
            If ``triangles`` is not (T, 3), an index is out of range, or
            ``groups`` does not have one name per triangle.
        TypeError
            If ``triangles`` is not an integer array.

        Examples
        --------
        A 20 x 20 m ground with a 3 m high wall along x = 10 from y = 0 to 8:

        >>> from attenuvis import visgraph as vg
        >>> vertices = [[0, 0, 0], [20, 0, 0], [20, 20, 0], [0, 20, 0],
        ...             [10, 0, 0], [10, 8, 0], [10, 8, 3], [10, 0, 3]]
        >>> triangles = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
        >>> vg.Scene.from_arrays(vertices, triangles, groups=["ground", "ground", "wall", "wall"])
        Scene(arrays, 4 triangles, groups=['ground', 'wall'])
        """
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
    def groups(self) -> List[str]:
        """Group names (OBJ ``g``/``o``, or materials), what ``walkable=`` selects."""
        return self._cpp.groups

    @property
    def warnings(self) -> List[str]:
        """What the reader noticed (an up axis that looks wrong, faces skipped)."""
        return self._cpp.warnings

    @property
    def crs(self) -> str:
        """The scene's coordinate reference system as its file names it ("" when unknown)."""
        return self._cpp.crs

    @property
    def ground(self) -> str:
        """Where the ground added to the scene came from ("" when none was added)."""
        return self._cpp.ground

    def __repr__(self) -> str:
        return f"Scene({self._cpp.format}, {self.triangle_count} triangles, groups={list(self.groups)})"


def _terrain(terrain) -> str:
    if terrain is None:
        return ""
    return os.fspath(terrain)


def classic_layout_names() -> List[str]:
    """Names of the classic layouts 0..4.

    Returns
    -------
    list of str
        The name of each index :meth:`Scene.layout` accepts.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> vg.classic_layout_names()
    ['four-L-walls', 'T-block', 'single-block', 'plus-block', 'two-walls']
    """
    return [_core.classic_layout_name(i) for i in range(5)]


def node_grid(scene: Scene, spacing: float, *, walkable: Optional[Sequence[str]] = None, eye_height: float = 1.7,
              max_slope_deg: float = 90.0) -> np.ndarray:
    """Eye points on a square grid over the surface people stand on.

    Parameters
    ----------
    scene : Scene
        The scene.
    spacing : float
        Grid pitch (m).
    walkable : sequence of str, optional
        Groups (or classes) people stand on; "*" = any surface.  None: the
        scene's own rule (shipped scenes: their floors and sidewalks; files:
        the lowest surface outside every solid, visgraph/nodes.hpp).
    eye_height : float, default 1.7
        Height of the eye above the surface (m).
    max_slope_deg : float, default 90
        Steepest surface (degrees from horizontal) that still carries a node.

    Returns
    -------
    numpy.ndarray of float64, shape (N, 3)
        The eye points x, y, z (m).

    Raises
    ------
    ValueError
        For a spacing outside its range or a ``walkable`` name that is
        neither a group nor a class of the scene.

    Examples
    --------
    >>> from attenuvis import visgraph as vg
    >>> eyes = vg.node_grid(vg.Scene.layout(2), 5.0)
    >>> eyes.shape
    (96, 3)
    >>> print(eyes[0])
    [2.5 2.5 1.7]
    """
    return _core.node_grid(scene._cpp, float(spacing), None if walkable is None else list(walkable),
                           float(eye_height), float(max_slope_deg))
