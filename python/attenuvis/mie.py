"""Lorenz-Mie scattering by a homogeneous sphere (attenuvis::mie).

Conventions (Bohren & Huffman 1983, "Absorption and Scattering of Light by
Small Particles", ch. 4, "B&H"):

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
|m| >= 0.5, all finite.  Within it the results agree with a 50-digit referee to
1e-10 relative (tests/mie/test_mie_referee.cpp).
"""

from __future__ import annotations

from typing import NamedTuple, Optional

import numpy as np

from . import _attenuvis

_core = _attenuvis.mie

__all__ = [
    "Efficiencies",
    "efficiencies",
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


class Efficiencies(NamedTuple):
    """Efficiencies of many spheres, each an array of the broadcast shape.

    qext, qsca, qabs, qback, qpr: dimensionless efficiencies (cross section /
    pi r^2); g: asymmetry parameter <cos theta>; terms: number of series terms
    summed (int64).  Elements that were bad with ``errors="nan"`` hold NaN
    (terms 0).
    """

    qext: np.ndarray
    qsca: np.ndarray
    qabs: np.ndarray
    qback: np.ndarray
    qpr: np.ndarray
    g: np.ndarray
    terms: np.ndarray


def _size_parameter(x, radius, wavelength, medium_index):
    if radius is None and wavelength is None:
        if x is None:
            raise TypeError("give x, or radius= and wavelength=")
        if medium_index is not None:
            raise TypeError("medium_index= goes with radius= and wavelength=, not with x")
        return x
    if x is not None:
        raise TypeError("give either x or radius= and wavelength=, not both")
    if radius is None or wavelength is None:
        raise TypeError("radius= and wavelength= go together")
    n_medium = 1.0 if medium_index is None else np.asarray(medium_index, dtype=np.float64)
    # x = 2 pi r n_medium / lambda_vacuum: lambda in the medium is lambda / n_medium.
    return 2.0 * np.pi * np.asarray(radius, dtype=np.float64) * n_medium / np.asarray(wavelength, dtype=np.float64)


def efficiencies(x=None, m=None, *, radius=None, wavelength=None, medium_index=None, errors="raise", threads=0):
    """Extinction, scattering, absorption, backscatter and radiation-pressure
    efficiencies and the asymmetry parameter of homogeneous spheres.

    Parameters
    ----------
    x : array_like of float
        Size parameters 2 pi r / lambda (lambda in the medium).  Or give
        ``radius`` and ``wavelength`` instead (same length unit, e.g. both in
        metres; ``wavelength`` in vacuum) and optionally ``medium_index``
        (real refractive index of the medium, default 1): then
        ``x = 2 pi radius medium_index / wavelength``.
    m : array_like of complex
        Refractive index of the sphere relative to the medium, ``n + ik``
        (B&H convention, k >= 0 absorbs).  With ``medium_index``, m is
        still the *relative* index (sphere / medium).
    errors : {"raise", "nan"}
        "raise" (default): a bad element (outside the domain above) raises
        ValueError naming its index and the reason.  "nan": bad elements are
        NaN in every output and the others are computed.
    threads : int
        Worker threads (0 = every core).  Results do not depend on it.

    Returns
    -------
    Efficiencies
        Named tuple of arrays with the broadcast shape of x and m (NumPy
        scalars when x and m are scalars).

    x and m broadcast together (NumPy rules); any real dtype and any strides
    are accepted (converted to contiguous float64/complex128 only when they
    are not already).  The work runs without the GIL; Ctrl-C interrupts it.

    Example: Bohren & Huffman's Appendix A sphere,
    ``efficiencies(3.0, 1.55).qext`` -> 3.10543.
    """
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    if m is None:
        raise TypeError("efficiencies() needs the refractive index m")
    x = _size_parameter(x, radius, wavelength, medium_index)
    x_in = np.asarray(x)
    m_in = np.asarray(m)
    if x_in.dtype.kind not in "biuf":
        raise TypeError(f"x must be real, got dtype {x_in.dtype}")
    if m_in.dtype.kind not in "biufc":
        raise TypeError(f"m must be a number, got dtype {m_in.dtype}")
    shape = np.broadcast_shapes(x_in.shape, m_in.shape)
    if m_in.ndim == 0:
        # One index for every sphere: no broadcast copy of m.
        x_flat = np.ascontiguousarray(np.broadcast_to(x_in, shape), dtype=np.float64).reshape(-1)
        m_arg = complex(m_in)
    else:
        xb, mb = np.broadcast_arrays(x_in, m_in)
        x_flat = np.ascontiguousarray(xb, dtype=np.float64).reshape(-1)
        m_arg = np.ascontiguousarray(mb, dtype=np.complex128).reshape(-1)
    qext, qsca, qabs, qback, qpr, g, terms, bad = _core.efficiencies(x_flat, m_arg, int(threads))
    if bad and errors == "raise":
        index, reason = bad[0]
        where = f"element {index}"
        if len(shape) > 1:
            where += f" (index {tuple(int(i) for i in np.unravel_index(index, shape))})"
        more = f" (and {len(bad) - 1} more bad elements)" if len(bad) > 1 else ""
        raise ValueError(f"{where}: {reason}{more}")
    # NumPy's rule: scalars in, scalars (0-d, np.float64) out.
    return Efficiencies(*(a.reshape(shape)[()] for a in (qext, qsca, qabs, qback, qpr, g, terms)))


def _one_sphere(x, m):
    x = float(x)
    m = complex(m)
    return x, m


def coefficients(x, m):
    """Mie coefficients a_n, b_n (B&H 4.53) of one sphere, n = 1..N.

    Returns two complex128 arrays of length N (index n-1), N the number of
    terms the converged series needs.
    """
    return _core.coefficients(*_one_sphere(x, m))


def amplitudes(x, m, angles):
    """Amplitude functions S1(theta), S2(theta) (B&H 4.74) of one sphere.

    ``angles``: scattering angles in degrees (0 = forward), any shape.
    Returns (S1, S2), complex128 arrays of the shape of ``angles``.
    S1(0) = S2(0) and qext = 4 Re S1(0) / x^2.
    """
    a = np.asarray(angles, dtype=np.float64)
    s1, s2 = _core.amplitudes(*_one_sphere(x, m), np.ascontiguousarray(a).reshape(-1))
    return s1.reshape(a.shape), s2.reshape(a.shape)


class ScatteringMatrix(NamedTuple):
    """B&H 4.77 scattering-matrix elements at the requested angles.

    s11, s12, s33, s34 unnormalised (integral of s11 over 4 pi sr is
    pi x^2 qsca); phase = 4 s11 / (x^2 qsca), normalised to 4 pi over the
    sphere (isotropic = 1).  Degree of linear polarisation = -s12/s11.
    """

    s11: np.ndarray
    s12: np.ndarray
    s33: np.ndarray
    s34: np.ndarray
    phase: np.ndarray


def scattering_matrix(x, m, angles):
    """Scattering matrix of one sphere at ``angles`` (degrees), see ScatteringMatrix."""
    a = np.asarray(angles, dtype=np.float64)
    d = _core.scattering_matrix(*_one_sphere(x, m), np.ascontiguousarray(a).reshape(-1))
    return ScatteringMatrix(**{k: v.reshape(a.shape) for k, v in d.items()})


def phase_function(x, m, angles, normalization="4pi"):
    """Phase function p(theta) of one sphere at ``angles`` (degrees).

    normalization: "4pi" (default, integral over the sphere = 4 pi, as
    DISORT/libRadtran), "1" (integral = 1, units 1/sr, Monte Carlo form), or
    "bh" (B&H's S11 itself, integral = pi x^2 qsca).
    """
    sm = scattering_matrix(x, m, angles)
    if normalization == "4pi":
        return sm.phase
    if normalization == "1":
        return sm.phase / (4.0 * np.pi)
    if normalization == "bh":
        return sm.s11
    raise ValueError(f"normalization must be '4pi', '1' or 'bh', not {normalization!r}")


def legendre_moments(x, m, L: Optional[int] = None):
    """Legendre moments chi_l of the phase function, l = 0..L.

    p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1, chi_1 = g: exactly DISORT's
    PMOM.  L = None gives every non-zero moment (l = 0..2N, N series terms);
    an L above 2N pads with exact zeros.  Accuracy: <= 1e-14 absolute against
    the 50-digit referee up to x = 1e4 (mie/legendre_moments.hpp).
    """
    return _core.legendre_moments(*_one_sphere(x, m), None if L is None else int(L))


class ScatteringMatrixExpansion(NamedTuple):
    """Generalised-spherical-function expansion (de Rooij & van der Stap 1984;
    Mishchenko, Travis & Lacis 2002, eqs. 4.75-4.80): alpha1..alpha4, beta1,
    beta2 for l = 0..L.  alpha1_l = (2l+1) chi_l; beta2 carries MTL's sign
    (opposite to B&H's S34)."""

    alpha1: np.ndarray
    alpha2: np.ndarray
    alpha3: np.ndarray
    alpha4: np.ndarray
    beta1: np.ndarray
    beta2: np.ndarray


def scattering_matrix_expansion(x, m, L: Optional[int] = None):
    """Polarised expansion of one sphere's scattering matrix, see ScatteringMatrixExpansion."""
    d = _core.scattering_matrix_expansion(*_one_sphere(x, m), None if L is None else int(L))
    return ScatteringMatrixExpansion(**d)


def phase_function_from_moments(chi, angles):
    """p(theta) = sum (2l+1) chi_l P_l(cos theta) at ``angles`` (degrees)."""
    a = np.asarray(angles, dtype=np.float64)
    p = _core.phase_function_from_moments(np.ascontiguousarray(chi, dtype=np.float64), a.reshape(-1))
    return p.reshape(a.shape)


class Lidar(NamedTuple):
    """Per-sphere lidar quantities (mie/scattering_matrix.hpp).

    backscatter_per_sr: Qback / (4 pi), the efficiency counterpart of the
    backscatter coefficient (1/(m sr) once multiplied by N pi r^2);
    lidar_ratio_sr: extinction-to-backscatter ratio 4 pi Qext / Qback (sr;
    inf where Qback = 0); linear_depolarisation: 0 for every homogeneous
    sphere (S22 = S11), so a measured non-zero value means non-spherical
    particles.
    """

    backscatter_per_sr: np.ndarray
    lidar_ratio_sr: np.ndarray
    linear_depolarisation: np.ndarray


def lidar(x=None, m=None, **kwargs):
    """Lidar quantities of spheres, broadcasting like efficiencies() (same
    arguments: x or radius=/wavelength=/medium_index=, errors=, threads=)."""
    q = efficiencies(x, m, **kwargs)
    qext, qback = np.asarray(q.qext), np.asarray(q.qback)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(qback > 0, 4.0 * np.pi * qext / qback, np.inf)
    ratio = np.where(np.isnan(qback), np.nan, ratio)
    return Lidar((qback / (4.0 * np.pi))[()], ratio[()], np.where(np.isnan(qback), np.nan, 0.0)[()])
