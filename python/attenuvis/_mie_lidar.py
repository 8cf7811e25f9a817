"""Lidar quantities of one sphere: backscatter, extinction and the lidar ratio.

Part of attenuvis.mie (its public names are re-exported there)."""

from __future__ import annotations

from typing import Any, NamedTuple, Optional
import numpy as np
from numpy.typing import ArrayLike

from . import _attenuvis
from ._mie_efficiencies import efficiencies

_core = _attenuvis.mie


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
