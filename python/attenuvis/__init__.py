"""attenuvis: Lorenz-Mie reference code, weather extinction models and a
weather-weighted Embree visibility graph, over NumPy arrays.

Modules:
    attenuvis.mie       efficiencies, amplitudes, scattering matrix, Legendre moments of spheres
    attenuvis.weather   conditions, size distributions, sigma, bulk optics, sigma tables
    attenuvis.visgraph  scenes, node grids, all-to-all and to-target visibility passes

Units are SI (metres, 1/m) unless a name says otherwise (rate_mm_h, ...);
refractive indices are m = n + ik (Bohren & Huffman).  The C++ core is the
extension module attenuvis._attenuvis; its errors arrive as ValueError
(bad input) or RuntimeError with the command line's message.

Examples
--------
>>> import attenuvis
>>> from attenuvis import mie, visgraph
>>> attenuvis.__version__  # doctest: +ELLIPSIS
'...'
>>> print(f"{mie.efficiencies(m=1.55, radius=0.525e-6, wavelength=0.6328e-6).qext:.5f}")
3.10543
>>> scene = visgraph.Scene.layout(2)
>>> r = visgraph.all_to_all(scene, visgraph.node_grid(scene, 5.0), [1.5e-4])
>>> print(r.degree[:4])
[76 75 72 70]
"""

from ._version import __version__
from . import mie, visgraph, weather

__all__ = ["__version__", "mie", "weather", "visgraph"]
