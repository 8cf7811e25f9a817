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
"""

from ._version import __version__
from . import mie, visgraph, weather

__all__ = ["__version__", "mie", "weather", "visgraph"]
