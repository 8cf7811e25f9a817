"""Efficiencies of homogeneous and layered spheres, NumPy arrays in and out.

Part of attenuvis.mie (its public names are re-exported there)."""

from __future__ import annotations

from typing import Literal, NamedTuple, Optional
import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis

_core = _attenuvis.mie


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
