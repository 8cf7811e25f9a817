"""Coefficients, amplitudes, the scattering matrix, the phase function and its Legendre moments.

Part of attenuvis.mie (its public names are re-exported there)."""

from __future__ import annotations

from typing import Literal, NamedTuple, Optional
import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis

_core = _attenuvis.mie


def _one_sphere(x, m):
    x = float(x)
    m = complex(m)
    return x, m


def coefficients(x: float, m: complex) -> tuple[np.ndarray, np.ndarray]:
    """Mie coefficients a_n, b_n (B&H 4.53) of one sphere, n = 1..N.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).

    Returns
    -------
    a, b : numpy.ndarray of complex128
        Arrays of length N (index n-1), N the number of terms the converged
        series needs.  Codes using ``m = n - ik`` (MIEV0) give their complex
        conjugates.

    Raises
    ------
    ValueError
        If x or m is outside the domain (see the module).

    Examples
    --------
    >>> from attenuvis import mie
    >>> a, b = mie.coefficients(1.0, 1.5)
    >>> len(a)
    11
    >>> print(f"{a[0]:.5f} {b[0]:.5f}")
    0.03487-0.18346j 0.00080-0.02828j
    """
    return _core.coefficients(*_one_sphere(x, m))


def amplitudes(x: float, m: complex, angles: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Amplitude functions S1(theta), S2(theta) (B&H 4.74) of one sphere.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    angles : array_like of float
        Scattering angles in degrees (0 = forward), any shape.

    Returns
    -------
    S1, S2 : numpy.ndarray of complex128
        Arrays of the shape of ``angles``.  S1(0) = S2(0), and
        qext = 4 Re S1(0) / x^2.

    Raises
    ------
    ValueError
        If x or m is outside the domain (see the module).

    Examples
    --------
    >>> from attenuvis import mie
    >>> s1, s2 = mie.amplitudes(1.0, 1.5, [0.0, 90.0, 180.0])
    >>> print(f"{s1[0]:.5f} {s2[0]:.5f}")
    0.05377-0.34615j 0.05377-0.34615j
    >>> print(f"{4 * s1[0].real / 1.0**2:.5f} {mie.efficiencies(1.0, 1.5).qext:.5f}")
    0.21510 0.21510
    """
    a = np.asarray(angles, dtype=np.float64)
    s1, s2 = _core.amplitudes(*_one_sphere(x, m), np.ascontiguousarray(a).reshape(-1))
    return s1.reshape(a.shape), s2.reshape(a.shape)


class ScatteringMatrix(NamedTuple):
    """B&H 4.77 scattering-matrix elements at the requested angles.

    Returned by :func:`scattering_matrix`; every field has the shape of the
    angles.  The degree of linear polarisation is -s12/s11.

    Attributes
    ----------
    s11, s12, s33, s34 : numpy.ndarray of float64
        Unnormalised elements: the integral of s11 over 4 pi sr is
        pi x^2 qsca.
    phase : numpy.ndarray of float64
        Phase function 4 s11 / (x^2 qsca), normalised to 4 pi over the
        sphere (isotropic = 1).

    Examples
    --------
    >>> from attenuvis import mie
    >>> sm = mie.scattering_matrix(1.0, 1.5, [90.0])
    >>> print(f"{-sm.s12[0] / sm.s11[0]:.5f}")
    0.99271
    """

    s11: np.ndarray
    s12: np.ndarray
    s33: np.ndarray
    s34: np.ndarray
    phase: np.ndarray


def scattering_matrix(x: float, m: complex, angles: ArrayLike) -> ScatteringMatrix:
    """Scattering matrix of one sphere at the given angles.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    angles : array_like of float
        Scattering angles in degrees (0 = forward), any shape.

    Returns
    -------
    ScatteringMatrix
        s11, s12, s33, s34 (B&H 4.77) and the phase function, each of the
        shape of ``angles``.

    Raises
    ------
    ValueError
        If x or m is outside the domain (see the module).

    Examples
    --------
    >>> import numpy as np
    >>> from attenuvis import mie
    >>> sm = mie.scattering_matrix(1.0, 1.5, [0.0, 90.0, 180.0])
    >>> print(np.round(sm.s11, 5))
    [0.12271 0.03879 0.04665]
    >>> print(np.round(sm.phase, 5))
    [2.28191 0.72134 0.86745]
    """
    a = np.asarray(angles, dtype=np.float64)
    d = _core.scattering_matrix(*_one_sphere(x, m), np.ascontiguousarray(a).reshape(-1))
    return ScatteringMatrix(**{k: v.reshape(a.shape) for k, v in d.items()})


def phase_function(x: float, m: complex, angles: ArrayLike,
                   normalization: Literal["4pi", "1", "bh"] = "4pi") -> np.ndarray:
    """Phase function p(theta) of one sphere at the given angles.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    angles : array_like of float
        Scattering angles in degrees (0 = forward), any shape.
    normalization : {"4pi", "1", "bh"}, default "4pi"
        "4pi": integral over the sphere = 4 pi, as DISORT/libRadtran
        (isotropic = 1).  "1": integral = 1, units 1/sr, the Monte Carlo
        form.  "bh": B&H's S11 itself, integral = pi x^2 qsca.

    Returns
    -------
    numpy.ndarray of float64
        p(theta), of the shape of ``angles``.

    Raises
    ------
    ValueError
        If x or m is outside the domain, or for an unknown ``normalization``.

    Examples
    --------
    >>> import numpy as np
    >>> from attenuvis import mie
    >>> print(np.round(mie.phase_function(1.0, 1.5, [0.0, 90.0, 180.0]), 5))
    [2.28191 0.72134 0.86745]

    The default normalisation: 1/2 times the integral over mu = cos theta is 1.

    >>> mu, w = np.polynomial.legendre.leggauss(64)
    >>> p = mie.phase_function(1.0, 1.5, np.degrees(np.arccos(mu)))
    >>> print(f"{0.5 * np.sum(w * p):.12f}")
    1.000000000000
    """
    sm = scattering_matrix(x, m, angles)
    if normalization == "4pi":
        return sm.phase
    if normalization == "1":
        return sm.phase / (4.0 * np.pi)
    if normalization == "bh":
        return sm.s11
    raise ValueError(f"normalization must be '4pi', '1' or 'bh', not {normalization!r}")


def legendre_moments(x: float, m: complex, L: Optional[int] = None) -> np.ndarray:
    """Legendre moments chi_l of one sphere's phase function, l = 0..L.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    L : int, optional
        Highest order.  None gives every non-zero moment (l = 0..2N, N series
        terms); an L above 2N pads with exact zeros.

    Returns
    -------
    numpy.ndarray of float64
        chi_0..chi_L with p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1 and
        chi_1 = g: exactly DISORT's PMOM.

    Raises
    ------
    ValueError
        If x or m is outside the domain (see the module).

    Notes
    -----
    Accuracy: <= 1e-14 absolute against the 50-digit referee up to x = 1e4
    (mie/legendre_moments.hpp).

    Examples
    --------
    >>> import numpy as np
    >>> from attenuvis import mie
    >>> chi = mie.legendre_moments(50, 1.33 + 1e-8j)
    >>> len(chi)
    163
    >>> print(np.round(chi[:3], 6))
    [1.       0.850727 0.769771]
    >>> print(mie.legendre_moments(1.0, 1.5, L=30)[-1])
    0.0
    """
    return _core.legendre_moments(*_one_sphere(x, m), None if L is None else int(L))


class ScatteringMatrixExpansion(NamedTuple):
    """Generalised-spherical-function expansion of a scattering matrix.

    Returned by :func:`scattering_matrix_expansion`; each field is an array
    over l = 0..L.

    Attributes
    ----------
    alpha1, alpha2, alpha3, alpha4 : numpy.ndarray of float64
        Expansion coefficients of the diagonal elements; alpha1_l =
        (2l+1) chi_l, so alpha1_0 = 1 and alpha1_1 = 3g.
    beta1, beta2 : numpy.ndarray of float64
        Expansion coefficients of the off-diagonal elements; beta2 carries
        MTL's sign (opposite to B&H's S34).

    References
    ----------
    J. F. de Rooij and C. C. A. H. van der Stap, Astron. Astrophys. 131, 237
    (1984).  M. I. Mishchenko, L. D. Travis and A. A. Lacis, *Scattering,
    Absorption, and Emission of Light by Small Particles*, Cambridge, 2002,
    eqs. 4.75-4.80 ("MTL").

    Examples
    --------
    >>> from attenuvis import mie
    >>> e = mie.scattering_matrix_expansion(1.0, 1.5)
    >>> print(f"{e.alpha1[0]:.1f} {e.alpha1[1] / 3:.6f}")
    1.0 0.198942
    """

    alpha1: np.ndarray
    alpha2: np.ndarray
    alpha3: np.ndarray
    alpha4: np.ndarray
    beta1: np.ndarray
    beta2: np.ndarray


def scattering_matrix_expansion(x: float, m: complex, L: Optional[int] = None) -> ScatteringMatrixExpansion:
    """Polarised expansion of one sphere's scattering matrix.

    Parameters
    ----------
    x : float
        Size parameter 2 pi r / lambda.
    m : complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    L : int, optional
        Highest order, as in :func:`legendre_moments` (None: l = 0..2N).

    Returns
    -------
    ScatteringMatrixExpansion
        alpha1..alpha4, beta1, beta2 for l = 0..L.

    Raises
    ------
    ValueError
        If x or m is outside the domain (see the module).

    Examples
    --------
    >>> import numpy as np
    >>> from attenuvis import mie
    >>> e = mie.scattering_matrix_expansion(1.0, 1.5, L=4)
    >>> print(np.round(e.alpha1, 6))
    [1.       0.596827 0.564749 0.109883 0.009914]
    """
    d = _core.scattering_matrix_expansion(*_one_sphere(x, m), None if L is None else int(L))
    return ScatteringMatrixExpansion(**d)


def phase_function_from_moments(chi: ArrayLike, angles: ArrayLike) -> np.ndarray:
    """Phase function from its Legendre moments, p(theta) = sum (2l+1) chi_l P_l(cos theta).

    Parameters
    ----------
    chi : array_like of float
        Legendre moments chi_0..chi_L (DISORT's PMOM, chi_0 = 1 for a
        phase function normalised to 4 pi), as from :func:`legendre_moments`.
    angles : array_like of float
        Scattering angles in degrees (0 = forward), any shape.

    Returns
    -------
    numpy.ndarray of float64
        p(theta), of the shape of ``angles``.

    Examples
    --------
    The moments of a sphere give back its phase function:

    >>> import numpy as np
    >>> from attenuvis import mie
    >>> chi = mie.legendre_moments(1.0, 1.5)
    >>> print(np.round(mie.phase_function_from_moments(chi, [0.0, 90.0, 180.0]), 5))
    [2.28191 0.72134 0.86745]
    """
    a = np.asarray(angles, dtype=np.float64)
    p = _core.phase_function_from_moments(np.ascontiguousarray(chi, dtype=np.float64), a.reshape(-1))
    return p.reshape(a.shape)
