"""Lorenz-Mie scattering by a homogeneous or layered sphere (attenuvis::mie).

Conventions (Bohren & Huffman 1983, ch. 4, "B&H"):

* time dependence exp(-i omega t); the relative refractive index is
  ``m = n + ik`` with ``k >= 0`` for an absorbing sphere (B&H's sign; codes
  using ``n - ik``, e.g. MIEV0, return complex conjugate amplitudes);
* size parameter ``x = 2 pi r / lambda``, lambda the wavelength in the medium,
  m the sphere's index divided by the medium's;
* efficiencies are cross sections over the geometric cross section pi r^2;
  ``qback = 4|S1(180 deg)|^2 / x^2`` (B&H 4.82; Draine's BHMIE returns this
  divided by 4 pi); ``g = <cos theta>``; ``qpr = qext - g qsca``;
* scattering angles in degrees, 0 = forward.

Domain (outside it an element is bad): 1e-8 <= x <= 1e6, 0 <= n, k <= 1e6,
``|m| >= 0.5``, all finite.  Within it the results agree with a 50-digit referee to
1e-10 relative (tests/mie/test_mie_referee.cpp).

References
----------
C. F. Bohren and D. R. Huffman, *Absorption and Scattering of Light by Small
Particles*, Wiley, 1983.

Examples
--------
Bohren & Huffman's Appendix A sphere (r = 0.525 um, lambda = 632.8 nm,
m = 1.55):

>>> from attenuvis import mie
>>> q = mie.efficiencies(m=1.55, radius=0.525e-6, wavelength=0.6328e-6)
>>> print(f"{q.qext:.5f} {q.qback:.5f}")
3.10543 2.92534
"""

from __future__ import annotations

from ._mie_efficiencies import Efficiencies, efficiencies, layered_efficiencies
from ._mie_angular import (
    ScatteringMatrix, ScatteringMatrixExpansion, amplitudes, coefficients, legendre_moments, phase_function,
    phase_function_from_moments, scattering_matrix, scattering_matrix_expansion
)
from ._mie_lidar import Lidar, lidar

__all__ = [
    "Efficiencies",
    "efficiencies",
    "layered_efficiencies",
    "coefficients",
    "amplitudes",
    "ScatteringMatrix",
    "scattering_matrix",
    "phase_function",
    "legendre_moments",
    "ScatteringMatrixExpansion",
    "scattering_matrix_expansion",
    "phase_function_from_moments",
    "Lidar",
    "lidar",
]


# The definitions live in the private modules above; they are documented,
# printed and pickled as this module's own.
for _name in __all__:
    globals()[_name].__module__ = __name__
del _name
