"""Particle size distributions: presets, parametric laws and tables.

Part of attenuvis.weather (its public names are re-exported there)."""

from __future__ import annotations

from typing import Dict

import numpy as np

from . import _attenuvis

_core = _attenuvis.weather


_RADIUS_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}
# number per volume of air per radius, in m^-4
_DENSITY_UNITS = {"m^-4": 1.0, "cm^-3 um^-1": 1e12, "m^-3 um^-1": 1e6, "m^-3 mm^-1": 1e3}


class Distribution:
    """A particle size distribution n(r) = dN/dr (SI inside: r in m, n in m^-4).

    Build one with `LogNormal`, `ModifiedGamma`, `Gamma`, `MarshallPalmer`,
    `GunnMarshall`, `PowerLaw`, `preset` or `tabulated`; the constructor
    itself takes the C++ object and is not meant to be called directly.

    Examples
    --------
    >>> d = LogNormal(number_per_m3=1e8, median_radius_m=4e-6, sigma_g=1.5)
    >>> d
    Distribution(log-normal N=1e+08 m^-3 r_g=4e-06 m sigma_g=1.5)
    >>> f"{d.moments()['effective_radius_m'] * 1e6:.4f}"
    '6.0333'
    """

    def __init__(self, cpp):
        self._cpp = cpp

    def density(self, radius_m):
        """The density n(r) at given radii.

        Parameters
        ----------
        radius_m : array_like of float
            Radii in metres, any shape.

        Returns
        -------
        numpy.ndarray
            n(r) in m^-4 (particles per m^3 of air per metre of radius), the
            shape of `radius_m`.

        Examples
        --------
        >>> d = ModifiedGamma(0.027, 3, 0.3)
        >>> n = d.density([1e-6, 1e-5])
        >>> n.shape, f"{n[0]:.6g}"
        ((2,), '2.00021e+10')
        """
        r = np.asarray(radius_m, dtype=np.float64)
        return self._cpp.density(r.reshape(-1)).reshape(r.shape)

    def moment(self, p: float) -> float:
        """The p-th moment, the integral of r^p n(r) dr over all r (SI).

        Parameters
        ----------
        p : float
            The order; 0 gives the number per m^3.

        Returns
        -------
        float
            In m^(p-3).

        Examples
        --------
        >>> f"{LogNormal(1e8, 4e-6, 1.5).moment(0):.6g}"
        '1e+08'
        """
        return self._cpp.moment(float(p))

    def moments(self, bulk_density_kg_m3: float = 1000.0) -> Dict[str, float]:
        """Number density, water content and characteristic radii.

        Parameters
        ----------
        bulk_density_kg_m3 : float, default 1000
            Density of the particles' material, for the water content (liquid
            water 1000, ice 917).

        Returns
        -------
        dict
            "number_per_m3", "water_content_kg_m3", "effective_radius_m"
            (<r^3>/<r^2>), "mode_radius_m" and "mean_radius_m", in SI.

        Examples
        --------
        >>> m = preset("advection").moments()
        >>> f"{m['number_per_m3'] * 1e-6:.4g} per cm^3, {m['water_content_kg_m3'] * 1e3:.4g} g/m^3"
        '20 per cm^3, 0.3723 g/m^3'
        """
        return self._cpp.moments(float(bulk_density_kg_m3))

    def scaled(self, factor: float) -> "Distribution":
        """The same shape with every density multiplied by ``factor``.

        Parameters
        ----------
        factor : float
            The multiplier (> 0).

        Returns
        -------
        Distribution

        Examples
        --------
        >>> f"{LogNormal(1e8, 4e-6, 1.5).scaled(2).moment(0):.6g}"
        '2e+08'
        """
        return Distribution(self._cpp.scaled(float(factor)))

    def to_number(self, number_per_m3: float) -> "Distribution":
        """The same shape rescaled to a number density.

        Parameters
        ----------
        number_per_m3 : float
            Particles per m^3 of air (> 0).

        Returns
        -------
        Distribution

        Raises
        ------
        ValueError
            When ``number_per_m3`` is not positive.

        Examples
        --------
        >>> f"{preset('radiation').to_number(1e9).moment(0):.6g}"
        '1e+09'
        """
        return Distribution(self._cpp.normalised_to_number(float(number_per_m3)))

    def to_water_content(self, kg_per_m3: float, bulk_density_kg_m3: float = 1000.0) -> "Distribution":
        """The same shape rescaled to a liquid (or ice) water content.

        Parameters
        ----------
        kg_per_m3 : float
            Water content in kg per m^3 of air (> 0).
        bulk_density_kg_m3 : float, default 1000
            Density of the particles' material (ice: 917).

        Returns
        -------
        Distribution

        Raises
        ------
        ValueError
            When either argument is not positive.

        Examples
        --------
        >>> d = preset("radiation").to_water_content(1e-4)
        >>> f"{d.moments()['water_content_kg_m3']:.6g}"
        '0.0001'
        """
        return Distribution(self._cpp.normalised_to_water_content(float(kg_per_m3), float(bulk_density_kg_m3)))

    def __repr__(self) -> str:
        return f"Distribution({self._cpp.describe()})"


def LogNormal(number_per_m3: float, median_radius_m: float, sigma_g: float) -> Distribution:
    """A log-normal distribution.

    n = N / (sqrt(2 pi) ln(sg) r) exp(-(ln r - ln rg)^2 / (2 ln^2 sg)).

    Parameters
    ----------
    number_per_m3 : float
        N, particles per m^3.
    median_radius_m : float
        rg, the median radius in metres.
    sigma_g : float
        sg > 1, the geometric standard deviation (the width).

    Returns
    -------
    Distribution

    Raises
    ------
    ValueError
        For a parameter outside its valid range.

    Examples
    --------
    >>> LogNormal(1e8, 4e-6, 1.5)
    Distribution(log-normal N=1e+08 m^-3 r_g=4e-06 m sigma_g=1.5)
    """
    return Distribution(_core.SizeDistribution.log_normal(number_per_m3, median_radius_m, sigma_g))


def ModifiedGamma(a: float, alpha: float, b: float, gamma: float = 1.0) -> Distribution:
    """A modified gamma distribution (Deirmendjian 1969) in P.1817-1 / seed units.

    n = a r^alpha exp(-b r^gamma), r in um, n in cm^-3 um^-1.

    Parameters
    ----------
    a, alpha, b : float
        The coefficient, the power and the exponential rate.
    gamma : float, default 1
        The power inside the exponential (P.1817-1 uses 1).

    Returns
    -------
    Distribution

    Examples
    --------
    >>> d = ModifiedGamma(0.027, 3, 0.3)  # P.1817-1 heavy advection fog
    >>> f"{d.moment(0) * 1e-6:.4g}"
    '20'
    """
    return Distribution(_core.SizeDistribution.modified_gamma_um(a, alpha, b, gamma))


def Gamma(number_per_m3: float, alpha: float, mode_radius_m: float) -> Distribution:
    """A gamma distribution n ~ r^alpha exp(-alpha r / r_mode).

    Parameters
    ----------
    number_per_m3 : float
        Particles per m^3.
    alpha : float
        The shape.
    mode_radius_m : float
        The radius where n peaks, in metres.

    Returns
    -------
    Distribution

    Examples
    --------
    >>> d = Gamma(1e8, 6, 5e-6)
    >>> f"{d.moments()['mode_radius_m'] * 1e6:.6g}"
    '5'
    """
    return Distribution(_core.SizeDistribution.gamma(number_per_m3, alpha, mode_radius_m))


def MarshallPalmer(rate_mm_h: float) -> Distribution:
    """Rain drops, Marshall & Palmer (1948).

    N(D) = N0 exp(-Lambda D) with N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1.

    Parameters
    ----------
    rate_mm_h : float
        Rain rate R in mm/h.

    Returns
    -------
    Distribution

    Examples
    --------
    >>> f"{MarshallPalmer(8).moment(0):.5g}"
    '3019.6'
    """
    return Distribution(_core.SizeDistribution.marshall_palmer(rate_mm_h))


def GunnMarshall(rate_mm_h: float) -> Distribution:
    """Snow, Gunn & Marshall (1958).

    N(D) = N0 exp(-Lambda D), N0 = 3800 R^-0.87 m^-3 mm^-1, Lambda = 2.55 R^-0.48 mm^-1.

    Parameters
    ----------
    rate_mm_h : float
        R, the melted precipitation rate in mm/h.

    Returns
    -------
    Distribution

    Examples
    --------
    >>> f"{GunnMarshall(2).moment(0):.5g}"
    '1137.2'
    """
    return Distribution(_core.SizeDistribution.gunn_marshall(rate_mm_h))


def PowerLaw(c_si: float, nu: float, r_min_m: float, r_max_m: float) -> Distribution:
    """A Junge power law n = c r^-nu (SI) on [r_min_m, r_max_m], zero outside.

    Parameters
    ----------
    c_si : float
        The coefficient c in SI (n in m^-4 with r in m).
    nu : float
        The power.
    r_min_m, r_max_m : float
        The radii the law holds between, in metres.

    Returns
    -------
    Distribution

    Examples
    --------
    >>> d = PowerLaw(1.0, 4.0, 1e-7, 1e-5)
    >>> f"{d.density([1e-6])[0]:.6g}"
    '1e+24'
    """
    return Distribution(_core.SizeDistribution.power_law(c_si, nu, r_min_m, r_max_m))


def preset(name: str) -> Distribution:
    """A named size distribution.

    Parameters
    ----------
    name : {'advection', 'radiation', 'marshall-palmer:R', 'gunn-marshall:R'}
        The P.1817-1 / seed fog presets, or rain or snow at R mm/h (e.g.
        "marshall-palmer:8"); registry("distribution_presets") lists them.

    Returns
    -------
    Distribution

    Raises
    ------
    ValueError
        Listing the presets, for any other name; naming the range, for a rate
        outside it.

    Examples
    --------
    >>> preset("advection")
    Distribution(heavy advection fog (P.1817-1: alpha=3, a=0.027, b=0.3; r um, n cm^-3 um^-1))
    >>> f"{preset('marshall-palmer:8').moment(0):.5g}"
    '3019.6'
    """
    return Distribution(_core.SizeDistribution.preset(name))


def tabulated(radius, density, *, radius_unit: str = "um", density_unit: str = "cm^-3 um^-1",
              source: str = "arrays") -> Distribution:
    """A piecewise-linear n(r) through the points (radius, density), zero outside.

    Parameters
    ----------
    radius : array_like of float
        Radii, increasing, at least two.
    density : array_like of float
        n(r) at those radii, each >= 0.
    radius_unit : {'m', 'mm', 'um', 'nm'}, default 'um'
    density_unit : {'m^-4', 'cm^-3 um^-1', 'm^-3 um^-1', 'm^-3 mm^-1'}, default 'cm^-3 um^-1'
        Number per volume of air per radius.
    source : str, default 'arrays'
        Names the distribution in descriptions and messages.

    Returns
    -------
    Distribution

    Raises
    ------
    ValueError
        For an unknown unit, or radii that do not increase or densities below
        0 (naming the index).

    Examples
    --------
    >>> d = tabulated([1, 2, 3], [0, 1, 0])  # a triangle, r in um, n in cm^-3 um^-1
    >>> f"{d.moment(0) * 1e-6:.6g}"
    '1'
    """
    if radius_unit not in _RADIUS_UNITS:
        raise ValueError(f"radius_unit must be one of {sorted(_RADIUS_UNITS)}, not {radius_unit!r}")
    if density_unit not in _DENSITY_UNITS:
        raise ValueError(f"density_unit must be one of {sorted(_DENSITY_UNITS)}, not {density_unit!r}")
    r = np.asarray(radius, dtype=np.float64) * _RADIUS_UNITS[radius_unit]
    n = np.asarray(density, dtype=np.float64) * _DENSITY_UNITS[density_unit]
    return Distribution(_core.SizeDistribution.from_arrays(r, n, source))
