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

from typing import Any, Literal, NamedTuple, Optional

import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis

_core = _attenuvis.mie

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


class Efficiencies(NamedTuple):
    """Efficiencies of many spheres, each an array of the broadcast shape.

    Returned by :func:`efficiencies`.  Elements that were bad with
    ``errors="nan"`` hold NaN (``terms`` 0).

    Attributes
    ----------
    qext, qsca, qabs, qback, qpr : numpy.ndarray of float64
        Extinction, scattering, absorption, backscatter and
        radiation-pressure efficiencies: dimensionless, cross section over
        pi r^2.
    g : numpy.ndarray of float64
        Asymmetry parameter <cos theta>.
    terms : numpy.ndarray of int64
        Number of series terms summed.

    Examples
    --------
    >>> from attenuvis import mie
    >>> q = mie.efficiencies(1.0, 1.5)
    >>> print(f"{q.qext:.5f} {q.qabs:.1f} {q.g:.5f} {q.terms}")
    0.21510 0.0 0.19894 11
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


def _checked_arrays(missing_m, x, m, radius, wavelength, medium_index, errors):
    """x (or radius and wavelength) and m as arrays of a real and a numeric dtype."""
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    if m is None:
        raise TypeError(missing_m)
    x_in = np.asarray(_size_parameter(x, radius, wavelength, medium_index))
    m_in = np.asarray(m)
    if x_in.dtype.kind not in "biuf":
        raise TypeError(f"x must be real, got dtype {x_in.dtype}")
    if m_in.dtype.kind not in "biufc":
        raise TypeError(f"m must be a number, got dtype {m_in.dtype}")
    return x_in, m_in


def efficiencies(x: Optional[ArrayLike] = None, m: Optional[ArrayLike] = None, *,
                 radius: Optional[ArrayLike] = None, wavelength: Optional[ArrayLike] = None,
                 medium_index: Optional[ArrayLike] = None, errors: Literal["raise", "nan"] = "raise",
                 threads: int = 0) -> Efficiencies:
    """Efficiencies and asymmetry parameter of homogeneous spheres.

    Extinction, scattering, absorption, backscatter and radiation-pressure
    efficiencies and g = <cos theta> of every sphere in the broadcast of
    ``x`` and ``m``.

    Parameters
    ----------
    x : array_like of float, optional
        Size parameters 2 pi r / lambda (lambda in the medium).  Or give
        ``radius`` and ``wavelength`` instead.
    m : array_like of complex
        Refractive index of the sphere relative to the medium, ``n + ik``
        (B&H convention, k >= 0 absorbs).  With ``medium_index``, m is
        still the *relative* index (sphere / medium).  Required.
    radius, wavelength : array_like of float, optional
        Sphere radius and vacuum wavelength in the same length unit (e.g.
        both in metres), given together instead of ``x``.
    medium_index : array_like of float, optional
        Real refractive index of the medium (default 1), only with
        ``radius`` and ``wavelength``: then
        ``x = 2 pi radius medium_index / wavelength``.
    errors : {"raise", "nan"}, default "raise"
        "raise": a bad element (outside the domain, see the module) raises
        ValueError.  "nan": bad elements are NaN in every output and the
        others are computed.
    threads : int, default 0
        Worker threads (0 = every core).  Results do not depend on it.

    Returns
    -------
    Efficiencies
        Named tuple of arrays with the broadcast shape of x and m (NumPy
        scalars when x and m are scalars).

    Raises
    ------
    ValueError
        With ``errors="raise"``, for the first bad element, naming its index
        and the reason (and how many more are bad); also for an ``errors``
        other than "raise" or "nan".
    TypeError
        If ``m`` is missing, if both or neither of ``x`` and
        ``radius``/``wavelength`` are given, or if x is not real or m not a
        number.
    KeyboardInterrupt
        On Ctrl-C, checked between chunks of the work.

    Notes
    -----
    x and m broadcast together (NumPy rules); any real dtype and any strides
    are accepted (converted to contiguous float64/complex128 only when they
    are not already).  The work runs without the GIL.

    Examples
    --------
    Bohren & Huffman's Appendix A sphere, x = 2 pi 0.525 / 0.6328:

    >>> import numpy as np
    >>> from attenuvis import mie
    >>> q = mie.efficiencies(m=1.55, radius=0.525e-6, wavelength=0.6328e-6)
    >>> print(f"{q.qext:.5f} {q.qsca:.5f} {q.qback:.5f} {q.g:.5f}")
    3.10543 3.10543 2.92534 0.63314

    A column of size parameters against a row of indices:

    >>> q = mie.efficiencies(np.array([0.1, 1.0, 10.0])[:, None], np.array([1.33 + 1e-8j, 1.5 + 0.1j]))
    >>> q.qext.shape
    (3, 2)
    >>> print(np.round(q.qext, 4))
    [[0.     0.0201]
     [0.0939 0.4824]
     [2.2065 2.4598]]

    Bad elements raise, or become NaN:

    >>> mie.efficiencies([1.0, -2.0], 1.33)
    Traceback (most recent call last):
    ...
    ValueError: element 1: mie: size parameter x must be finite and in [1e-08, 1000000], got -2
    >>> print(np.round(mie.efficiencies([1.0, -2.0], 1.33, errors="nan").qext, 5))
    [0.09392     nan]
    """
    x_in, m_in = _checked_arrays("efficiencies() needs the refractive index m", x, m, radius, wavelength,
                                 medium_index, errors)
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
        _raise_first_bad(bad, shape)
    # NumPy's rule: scalars in, scalars (0-d, np.float64) out.
    return Efficiencies(*(a.reshape(shape)[()] for a in (qext, qsca, qabs, qback, qpr, g, terms)))


def _raise_first_bad(bad, shape):
    index, reason = bad[0]
    where = f"element {index}"
    if len(shape) > 1:
        where += f" (index {tuple(int(i) for i in np.unravel_index(index, shape))})"
    more = f" (and {len(bad) - 1} more bad elements)" if len(bad) > 1 else ""
    raise ValueError(f"{where}: {reason}{more}")


def layered_efficiencies(x: Optional[ArrayLike] = None, m: Optional[ArrayLike] = None, *,
                         radius: Optional[ArrayLike] = None, wavelength: Optional[ArrayLike] = None,
                         medium_index: Optional[ArrayLike] = None, errors: Literal["raise", "nan"] = "raise",
                         threads: int = 0) -> Efficiencies:
    """Efficiencies and asymmetry parameter of layered (core-shell) spheres.

    The last axis of ``x`` and ``m`` lists the layers of one particle from
    the core out; the leading axes broadcast as in :func:`efficiencies`.

    Parameters
    ----------
    x : array_like of float, shape (..., L), optional
        Size parameter 2 pi r_l / lambda of the *outer* radius of each layer,
        non-decreasing from the core out (lambda in the medium).  Or give
        ``radius`` and ``wavelength`` instead.
    m : array_like of complex, shape (..., L)
        Refractive index of each layer relative to the medium, ``n + ik``
        (k >= 0 absorbs).  Required.
    radius, wavelength : array_like of float, optional
        Outer radius of each layer (shape (..., L)) and the vacuum wavelength,
        in the same length unit, given together instead of ``x``.
    medium_index : array_like of float, optional
        Real refractive index of the medium (default 1), only with
        ``radius`` and ``wavelength``.
    errors : {"raise", "nan"}, default "raise"
        As for :func:`efficiencies`: a bad particle raises ValueError, or
        becomes NaN with "nan".
    threads : int, default 0
        Worker threads (0 = every core).  Results do not depend on it.

    Returns
    -------
    Efficiencies
        Named tuple of arrays of the broadcast shape without the layer axis;
        efficiencies refer to the cross section of the outer radius.

    Raises
    ------
    ValueError
        With ``errors="raise"``, for the first bad particle (its index and
        the reason, which names the layer); for mismatched layer axes.
    TypeError
        As for :func:`efficiencies`, and when x or m has no layer axis.

    Notes
    -----
    One layer is exactly :func:`efficiencies` (the same bits).  Accuracy:
    within 1e-10 of a 50-digit referee of the same equations on the stress
    grid of the C++ tests (core x 1e-4 ... 1e4, shells of 1e-3 ... 10 core
    radii, indices 1.0001 ... 10+10i).

    Examples
    --------
    Soot (r = 0.5 um) coated with sulphate (outer r = 1 um) at 550 nm:

    >>> import numpy as np
    >>> from attenuvis import mie
    >>> q = mie.layered_efficiencies(m=[1.75 + 0.44j, 1.43 + 1e-8j], radius=[0.5e-6, 1.0e-6],
    ...                              wavelength=0.55e-6)
    >>> print(f"{q.qext:.6f} {q.qabs:.6f} {q.g:.6f}")
    1.864976 0.607507 0.584558

    The coating grown from nothing to twice the core radius, one particle
    per row of x:

    >>> core = 2.0
    >>> x = np.stack([np.full(3, core), core * np.array([1.0, 1.5, 2.0])], axis=-1)
    >>> print(np.round(mie.layered_efficiencies(x, [1.75 + 0.44j, 1.43 + 1e-8j]).qabs, 4))
    [1.5123 1.0073 0.592 ]

    The first row has a shell of zero thickness: it is the bare core.

    >>> print(f"{mie.efficiencies(core, 1.75 + 0.44j).qabs:.4f}")
    1.5123
    """
    x_in, m_in = _checked_arrays("layered_efficiencies() needs the refractive indices m", x, m, radius,
                                 wavelength, medium_index, errors)
    if x_in.ndim == 0 or m_in.ndim == 0:
        raise TypeError("x and m need a last axis listing the layers")
    try:
        full = np.broadcast_shapes(x_in.shape, m_in.shape)
    except ValueError as e:
        raise ValueError(f"x {x_in.shape} and m {m_in.shape} do not broadcast: {e}") from None
    layers = full[-1]
    shape = full[:-1]
    xb, mb = np.broadcast_arrays(x_in, m_in)
    x_flat = np.ascontiguousarray(xb, dtype=np.float64).reshape(-1)
    m_flat = np.ascontiguousarray(mb, dtype=np.complex128).reshape(-1)
    qext, qsca, qabs, qback, qpr, g, terms, bad = _core.layered_efficiencies(x_flat, m_flat, int(layers),
                                                                            int(threads))
    if bad and errors == "raise":
        _raise_first_bad(bad, shape)
    return Efficiencies(*(a.reshape(shape)[()] for a in (qext, qsca, qabs, qback, qpr, g, terms)))


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


class Lidar(NamedTuple):
    """Per-sphere lidar quantities (mie/scattering_matrix.hpp).

    Returned by :func:`lidar`; arrays of the broadcast shape of x and m.

    Attributes
    ----------
    backscatter_per_sr : numpy.ndarray of float64
        Qback / (4 pi), the efficiency counterpart of the backscatter
        coefficient (1/(m sr) once multiplied by N pi r^2).
    lidar_ratio_sr : numpy.ndarray of float64
        Extinction-to-backscatter ratio 4 pi Qext / Qback (sr; inf where
        Qback = 0).
    linear_depolarisation : numpy.ndarray of float64
        0 for every homogeneous sphere (S22 = S11), so a measured non-zero
        value means non-spherical particles.

    Examples
    --------
    >>> from attenuvis import mie
    >>> print(mie.lidar(1.0, 1.5).linear_depolarisation)
    0.0
    """

    backscatter_per_sr: np.ndarray
    lidar_ratio_sr: np.ndarray
    linear_depolarisation: np.ndarray


def lidar(x: Optional[ArrayLike] = None, m: Optional[ArrayLike] = None, **kwargs: Any) -> Lidar:
    """Lidar quantities of spheres, broadcasting like :func:`efficiencies`.

    Parameters
    ----------
    x : array_like of float, optional
        Size parameters, or give ``radius=`` and ``wavelength=``.
    m : array_like of complex
        Relative refractive index ``n + ik`` (k >= 0 absorbs).
    **kwargs
        The other arguments of :func:`efficiencies`: ``radius``,
        ``wavelength``, ``medium_index``, ``errors``, ``threads``.

    Returns
    -------
    Lidar
        Backscatter per steradian, lidar ratio and linear depolarisation,
        NaN where an element was bad with ``errors="nan"``.

    Raises
    ------
    ValueError, TypeError
        As :func:`efficiencies`.

    Examples
    --------
    A 1 um water droplet at 1064 nm:

    >>> from attenuvis import mie
    >>> l = mie.lidar(m=1.33 + 1e-8j, radius=1e-6, wavelength=1064e-9)
    >>> print(f"{l.backscatter_per_sr:.5f} {l.lidar_ratio_sr:.2f}")
    0.03634 107.63
    """
    q = efficiencies(x, m, **kwargs)
    qext, qback = np.asarray(q.qext), np.asarray(q.qback)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(qback > 0, 4.0 * np.pi * qext / qback, np.inf)
    ratio = np.where(np.isnan(qback), np.nan, ratio)
    return Lidar((qback / (4.0 * np.pi))[()], ratio[()], np.where(np.isnan(qback), np.nan, 0.0)[()])
