"""Weather conditions, particle size distributions and their extinction
(attenuvis::weather).

Units: wavelengths in metres (550e-9 for 550 nm), extinction coefficients
sigma in 1/m (nepers per metre; multiply by 4343 for dB/km), distances in
metres, rain and snow rates in mm/h.  Refractive indices m = n + ik (k >= 0
absorbing, Bohren & Huffman's convention).

Conditions mirror the typed C++ conditions (weather/condition.hpp)::

    Clear()                      seed paper's clear air, sigma = 1.5e-4 1/m
    Clear(visibility=20e3)       Koschmieder from a visibility
    Visibility(5000)             any atmosphere of that visibility
    Sigma(2e-3)                  a given sigma, 1/m
    Rain(8)                      P.1817-1-style power law (model: a rain power law)
    Rain(8, model="mie")         Mie over Marshall-Palmer drops
    Snow(4, type="dry")          P.1817-1 snow (type: a snow type)
    Fog("advection")             Mie over a P.1817-1 / seed fog preset
    Fog(visibility=500, model="kim")   empirical fog from a visibility (model: a visibility fog model)
    Fog(distribution=LogNormal(...), m=1.33+1e-8j)   Mie over your own drops
    Haze("urban", rh=80)         an OPAC aerosol type at a relative humidity (type: an aerosol mixture)
    Aerosol({"waso": 7000, "soot": 8300}, rh=70)     your own mixture of OPAC components, per cm^3

The names a condition takes (rain power laws, snow types, fog presets,
visibility fog models, water tables, aerosol components, mixtures and humidity
rules) and the quantities of a table are the
C++ library's: ``registry(kind)`` lists each kind with units, help and
citation.  ``parse("fog:advection")`` reads the command line's grammar
(``grammar()``).  Power laws are read per the ``convention`` argument ("itu",
the default, or "seed"; README, units).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from . import _attenuvis

_core = _attenuvis.weather

__all__ = [
    "Condition", "Clear", "Visibility", "Sigma", "Rain", "Snow", "Fog", "Haze", "Aerosol",
    "Distribution", "LogNormal", "ModifiedGamma", "Gamma", "MarshallPalmer", "GunnMarshall", "PowerLaw",
    "preset", "tabulated",
    "parse", "expand", "grammar", "sigma", "optics", "table", "refractive_index",
    "registry", "registry_kinds",
    "SigmaResult", "Estimate", "Optics", "Table",
]

# ---- the names of the C++ registries ------------------------------------------


def registry_kinds() -> List[str]:
    """The kinds of name the library accepts.

    Returns
    -------
    list of str
        Each a valid argument of `registry`.

    Examples
    --------
    >>> registry_kinds()  # doctest: +NORMALIZE_WHITESPACE
    ['water_tables', 'fog_presets', 'distribution_presets', 'rain_power_laws', 'snow_types',
     'visibility_fog_models', 'table_quantities', 'aerosol_components', 'aerosol_mixtures', 'humidity_rules']
    """
    return list(_core.registry_kinds())


def registry(kind: str) -> List[Dict[str, Any]]:
    """Every name of one kind, as the C++ library lists it (weather/registry.hpp).

    The condition grammar, the command line's help and this module all read
    these lists, so they are the one place a name is defined.

    Parameters
    ----------
    kind : str
        One of `registry_kinds()`: "water_tables", "fog_presets",
        "distribution_presets", "rain_power_laws", "snow_types",
        "visibility_fog_models", "table_quantities", "aerosol_components",
        "aerosol_mixtures" or "humidity_rules".

    Returns
    -------
    list of dict
        One dict per name, in the library's order, with the keys "name",
        "units" ("" where none is meaningful), "help" and "citation" ("" where
        there is none), and what else the kind knows (a water table's
        "aliases" and "file", a power law's "k" and "alpha", a table
        quantity's "python_name", ...).

    Raises
    ------
    ValueError
        For a kind that is not one of `registry_kinds()`.

    Examples
    --------
    >>> [e["name"] for e in registry("rain_power_laws")]
    ['seed', 'carbonneau', 'p1814']
    >>> seed = registry("rain_power_laws")[0]
    >>> seed["k"], seed["alpha"], seed["default"]
    (1.17, 0.65, True)
    >>> registry("water_tables")[0]["aliases"]
    ['water']
    >>> urban = registry("aerosol_mixtures")[3]
    >>> urban["name"], urban["waso"], urban["soot"]
    ('urban', 28000.0, 130000.0)
    """
    return list(_core.registry(kind))


def _named(kind: str) -> Dict[str, Dict[str, Any]]:
    """name -> entry for one registry kind, aliases included."""
    out = {}
    for entry in _core.registry(kind):
        out[entry["name"]] = entry
        for alias in entry.get("aliases", []):
            out[alias] = entry
    return out


# The names each parameter takes, read once from the C++ registries.
_WATER_TABLES = _named("water_tables")
_FOG_PRESETS = _named("fog_presets")
_FOG_MODELS = _named("visibility_fog_models")
_RAIN_LAWS = _named("rain_power_laws")
_SNOW_TYPES = _named("snow_types")
_AEROSOL_COMPONENTS = _named("aerosol_components")
_AEROSOL_MIXTURES = _named("aerosol_mixtures")
_HUMIDITY_RULES = _named("humidity_rules")
# Table quantities by their Python name (the Optics attribute they read; "sigma" for sigma_ext).
_TABLE_QUANTITIES = {e["python_name"]: e for e in _core.registry("table_quantities")}


def _enum_value(enum, name: str):
    """The bound C++ enum's value for a registry name ('-' becomes '_' there)."""
    return getattr(enum, name.replace("-", "_"))


def _enum_name(value) -> str:
    """The registry name of a bound C++ enum value."""
    return value.name.replace("_", "-")


def _at_most_one(**given) -> None:
    """TypeError "give a= or b=, not both" when more than one of the keywords is set."""
    named = [name for name, value in given.items() if value is not None]
    if len(named) > 1:
        raise TypeError(f"give {named[0]}= or {named[1]}=, not both")


# ---- size distributions -----------------------------------------------------

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


# ---- conditions ---------------------------------------------------------------


class Condition:
    """A weather condition; ``text`` is the command line's spelling of it.

    The subclasses `Clear`, `Visibility`, `Sigma`, `Rain`, `Snow` and `Fog`
    build one; `parse` reads one from its text.

    Examples
    --------
    >>> Rain(8).text
    'rain:8:seed'
    >>> parse("rain:8:seed")
    Rain('rain:8:seed')
    """

    _cpp: Any = None  # the typed C++ condition, or None for a Python-only one

    @property
    def text(self) -> str:
        """The condition in the command line's grammar (`grammar`)."""
        return _core.to_text(self._cpp)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.text!r})"


class Clear(Condition):
    """Clear air.

    Parameters
    ----------
    visibility : float, optional
        A visibility in metres: sigma from Koschmieder's law.  Without it the
        seed paper's sigma = 1.5e-4 1/m.

    Examples
    --------
    >>> sigma(Clear()).value
    0.00015
    >>> Clear(visibility=20e3).text
    'clear:20000m'
    """

    def __init__(self, visibility: Optional[float] = None):
        self.visibility = visibility
        self._cpp = _core.ClearAir(None if visibility is None else float(visibility))


class Visibility(Condition):
    """Any atmosphere of a given meteorological visibility (Koschmieder).

    Parameters
    ----------
    distance : float
        The visibility in metres.

    Examples
    --------
    >>> f"{sigma(Visibility(1000)).value:.6g}"  # ln(1/0.02) / 1000 m
    '0.00391202'
    """

    def __init__(self, distance: float):
        self.distance = float(distance)
        self._cpp = _core.Visibility(self.distance)


class Sigma(Condition):
    """A given extinction coefficient.

    Parameters
    ----------
    per_m : float
        sigma in 1/m.

    Examples
    --------
    >>> Sigma(2e-3).text
    'sigma:0.002'
    """

    def __init__(self, per_m: float):
        self.per_m = float(per_m)
        self._cpp = _core.GivenSigma(self.per_m)


def _index_source(m, water, index=None):
    _at_most_one(m=m, water=water, index=index)
    if index is not None:
        return _core.IndexFile(str(index))
    if m is not None:
        return _core.ConstantIndex(complex(m))
    if water is not None:
        if water not in _WATER_TABLES:
            raise ValueError(f"water must be one of {sorted(_WATER_TABLES)}, not {water!r}")
        return _enum_value(_core.WaterTable, _WATER_TABLES[water]["name"])
    return _core.SettingsWaterTable()


def _rescaling(number_density, lwc):
    _at_most_one(number_density=number_density, lwc=lwc)
    if number_density is not None:
        return _core.NumberDensity(float(number_density))
    if lwc is not None:
        return _core.LiquidWaterContent(float(lwc))
    return _core.AsGiven()


class Rain(Condition):
    """Rain, as a power law or as Mie scattering by its drops.

    Parameters
    ----------
    rate : float
        Rain rate in mm/h.
    model : {'seed', 'carbonneau', 'p1814', 'mie'}, default 'seed'
        A P.1817-1-style power law gamma = k R^alpha, read per the
        convention (registry("rain_power_laws") gives k, alpha and the
        sources), or "mie": Mie over Marshall-Palmer drops.
    m : complex, optional
        With model "mie": a constant refractive index instead of the water table.
    water : {'hale-querry', 'water', 'segelstein', 'ice'}, optional
        With model "mie": the refractive-index table ("water" is
        "hale-querry"); default: the ``water_table`` of `sigma`.

    Raises
    ------
    ValueError
        For an unknown model or water table.
    TypeError
        For m= or water= with a power law, or both together.

    Examples
    --------
    >>> Rain(8, model="carbonneau").text
    'rain:8:carbonneau'
    >>> f"{sigma(Rain(8)).value:.6g}"  # 1.17 R^0.65 dB/km, in 1/m
    '0.0010409'
    >>> Rain(8, model="mie", water="ice").text
    'rain:8:mie:water=ice'
    """

    def __init__(self, rate: float, model: str = "seed", *, m=None, water=None):
        self.rate = float(rate)
        self.model = model
        if model == "mie":
            self._cpp = _core.MieCondition(_core.MarshallPalmerRain(self.rate), _index_source(m, water), _core.AsGiven())
        else:
            if model not in _RAIN_LAWS:
                raise ValueError(f"rain model must be one of {', '.join([*_RAIN_LAWS, 'mie'])}, not {model!r}")
            if m is not None or water is not None:
                raise TypeError("m= and water= apply to model='mie' only")
            self._cpp = _core.RainPowerLaw(self.rate, _enum_value(_core.RainLaw, model))


class Snow(Condition):
    """Snow after ITU-R P.1817-1: gamma = a(lambda) S^b, read per the convention.

    Parameters
    ----------
    rate : float
        The melted precipitation rate S in mm/h.
    type : {'dry', 'wet'}, default 'dry'
        registry("snow_types") gives a(lambda) and b of each.

    Raises
    ------
    ValueError
        For an unknown type.

    Examples
    --------
    >>> Snow(4, "wet").text
    'snow:wet:4'
    """

    def __init__(self, rate: float, type: str = "dry"):
        self.rate = float(rate)
        self.type = type
        if type not in _SNOW_TYPES:
            raise ValueError(f"snow type must be {' or '.join(repr(t) for t in sorted(_SNOW_TYPES))}, not {type!r}")
        self._cpp = _core.Snow(_enum_value(_core.SnowType, type), self.rate)


class Fog(Condition):
    """Fog, in one of three ways: a preset, an empirical model or your own drops.

    Give exactly one of ``preset``, ``visibility``, ``distribution`` or ``file``.

    Parameters
    ----------
    preset : {'advection', 'radiation'}, optional
        Mie over the P.1817-1 / seed preset drops (registry("fog_presets")).
    visibility : float, optional
        A visibility in metres, for the empirical ``model``.
    model : {'kruse', 'kim', 'naboulsi-advection', 'naboulsi-radiation'}, default 'kim'
        The empirical model from the visibility (registry("visibility_fog_models")).
    distribution : Distribution, optional
        Mie over your own drops (index from ``m``, else the water table at
        each wavelength).
    file : str, optional
        Mie over the drops of a size-distribution CSV file (the command
        line's fog:file=PATH).
    m : complex, optional
        A constant refractive index instead of the water table.
    water : {'hale-querry', 'water', 'segelstein', 'ice'}, optional
        The refractive-index table ("water" is "hale-querry"); default: the
        ``water_table`` of `sigma`.
    index : str, optional
        A refractive-index file instead: refractiveindex.info YAML (.yml) or
        three columns um, n, k (the command line's :index=FILE).
    number_density : float, optional
        Rescale the drops to this many particles per cm^3.
    lwc : float, optional
        Rescale the drops to this liquid water content, g/m^3.

    Raises
    ------
    TypeError
        Unless exactly one of preset, visibility, distribution and file is
        given, or for both m= and water= (number_density= and lwc=).
    ValueError
        For an unknown preset, model or water table.

    Examples
    --------
    >>> Fog("advection", water="segelstein").text
    'fog:advection:water=segelstein'
    >>> Fog(visibility=500, model="naboulsi-advection").text
    'fog:naboulsi-advection:500m'
    >>> f"{sigma(Fog('radiation'), 10.6e-6).value:.6g}"
    '0.00193455'
    """

    def __init__(self, preset: Optional[str] = None, *, visibility: Optional[float] = None, model: str = "kim",
                 distribution: Optional[Distribution] = None, m=None, water=None,
                 number_density: Optional[float] = None, lwc: Optional[float] = None, file: Optional[str] = None,
                 index: Optional[str] = None):
        given = [preset is not None, visibility is not None, distribution is not None, file is not None]
        if sum(given) != 1:
            raise TypeError("Fog needs exactly one of: a preset name, visibility=, distribution=, file=")
        self.distribution = distribution
        self.m = m
        self.water = water
        if distribution is not None:
            if number_density is not None:
                distribution = distribution.to_number(number_density * 1e6)
            if lwc is not None:
                distribution = distribution.to_water_content(lwc * 1e-3)
            self.distribution = distribution
            self._cpp = None
        elif visibility is not None:
            if model not in _FOG_MODELS:
                raise ValueError(f"fog model must be one of {sorted(_FOG_MODELS)}, not {model!r}")
            self._cpp = _core.FogFromVisibility(_enum_value(_core.VisibilityFogModel, model), float(visibility))
        else:
            if file is not None:
                drops = _core.DistributionFile(str(file))
            elif preset in _FOG_PRESETS:
                drops = _enum_value(_core.FogPreset, preset)
            else:
                names = " or ".join(repr(p) for p in _FOG_PRESETS)
                raise ValueError(f"fog preset must be {names}, not {preset!r}")
            self._cpp = _core.MieCondition(drops, _index_source(m, water, index), _rescaling(number_density, lwc))

    @property
    def text(self) -> str:
        """The condition in the command line's grammar; a Python-only
        distribution reads "fog:distribution(...)"."""
        if self._cpp is None:
            return f"fog:distribution({self.distribution._cpp.describe()})"
        return _core.to_text(self._cpp)


def _aerosol_options(rh, growth, visibility, mass):
    """The typed humidity rule and scaling of an aerosol, checked against the registries."""
    if growth not in _HUMIDITY_RULES:
        raise ValueError(f"growth must be one of {', '.join(_HUMIDITY_RULES)}, not {growth!r}")
    _at_most_one(visibility=visibility, mass=mass)
    if visibility is not None:
        scaling = _core.ScaledToVisibility(float(visibility))
    elif mass is not None:
        scaling = _core.ScaledToDryMass(float(mass))
    else:
        scaling = _core.AsGiven()
    return float(rh), _enum_value(_core.HumidityRule, growth), scaling


def _checked_aerosol(cpp):
    """The typed aerosol, its numbers range-checked by the C++ grammar (the one set of rules and messages)."""
    return _core.parse(_core.to_text(cpp))


class Haze(Condition):
    """An OPAC aerosol type at a relative humidity (Hess, Koepke & Schult 1998).

    The components' number densities are OPAC's (registry("aerosol_mixtures"));
    hygroscopic components grow with humidity by the ``growth`` rule
    (registry("humidity_rules")).

    Parameters
    ----------
    type : {'continental-clean', 'continental-average', 'continental-polluted', 'urban', 'desert', 'maritime-clean', 'maritime-polluted', 'maritime-tropical', 'arctic', 'antarctic'}
        The aerosol type.
    rh : float
        Relative humidity in percent, 0 to 99.
    growth : {'kappa', 'linear', 'nearest'}, default 'kappa'
        How a humidity between OPAC's tabulated ones is reached.
    visibility : float, optional
        Scale the number densities so that the Koschmieder visibility at
        550 nm is this many metres.
    mass : float, optional
        Scale the number densities to this dry mass concentration, ug/m^3.

    Raises
    ------
    ValueError
        For an unknown type or rule, or a humidity outside [0, 99].
    TypeError
        For both visibility= and mass=.

    Examples
    --------
    >>> Haze("urban", rh=95).text
    'haze:urban:rh=95'
    >>> f"{sigma(Haze('urban', rh=0)).value:.4g}"
    '0.0001941'
    >>> Haze("maritime-clean", rh=80, visibility=10e3).text
    'haze:maritime-clean:rh=80:visibility=10000m'
    """

    def __init__(self, type: str, rh: float, *, growth: str = "kappa", visibility: Optional[float] = None,
                 mass: Optional[float] = None):
        if type not in _AEROSOL_MIXTURES:
            raise ValueError(f"aerosol type must be one of {', '.join(_AEROSOL_MIXTURES)}, not {type!r}")
        self.type, self.rh, self.growth, self.visibility, self.mass = type, float(rh), growth, visibility, mass
        mixture = _enum_value(_core.AerosolMixture, type)
        self._cpp = _checked_aerosol(_core.AerosolCondition(mixture, _core.mixture_amounts(mixture),
                                                            *_aerosol_options(rh, growth, visibility, mass)))


class Aerosol(Condition):
    """Your own external mixture of OPAC components at a relative humidity.

    Parameters
    ----------
    components : dict
        Number density in particles per cm^3 by component name, each of
        'inso', 'waso', 'soot', 'ssam', 'sscm', 'minm', 'miam', 'micm',
        'mitr', 'suso' (registry("aerosol_components")).
    rh : float
        Relative humidity in percent, 0 to 99.
    growth : {'kappa', 'linear', 'nearest'}, default 'kappa'
        How a humidity between OPAC's tabulated ones is reached.
    visibility : float, optional
        Scale the number densities to this visibility (m) at 550 nm.
    mass : float, optional
        Scale them to this dry mass concentration, ug/m^3.

    Raises
    ------
    ValueError
        For an unknown component or rule, a number density or humidity out of
        range.

    Examples
    --------
    >>> a = Aerosol({"waso": 7000, "soot": 8300, "inso": 0.4}, rh=70)
    >>> a.text
    'aerosol:waso=7000,soot=8300,inso=0.4:rh=70'
    >>> parse(a.text).components
    {'waso': 7000.0, 'soot': 8300.0, 'inso': 0.4}
    """

    def __init__(self, components: Dict[str, float], rh: float, *, growth: str = "kappa",
                 visibility: Optional[float] = None, mass: Optional[float] = None):
        amounts = []
        for name, n in components.items():
            if name not in _AEROSOL_COMPONENTS:
                raise ValueError(f"aerosol component must be one of {', '.join(_AEROSOL_COMPONENTS)}, not {name!r}")
            amounts.append(_core.AerosolAmount(_enum_value(_core.AerosolComponent, name), float(n)))
        self.components = {name: float(n) for name, n in components.items()}
        self.rh, self.growth, self.visibility, self.mass = float(rh), growth, visibility, mass
        self._cpp = _checked_aerosol(_core.AerosolCondition(None, amounts, *_aerosol_options(rh, growth, visibility,
                                                                                              mass)))


def _aerosol_from_cpp(cpp, make) -> Condition:
    """A Haze or an Aerosol with its fields read back from the typed C++ aerosol."""
    scaling = cpp.scaling
    fields = dict(rh=cpp.relative_humidity_percent, growth=_enum_name(cpp.humidity_rule),
                  visibility=getattr(scaling, "visibility_m", None), mass=getattr(scaling, "ug_per_m3", None))
    if cpp.mixture is not None:
        return make(Haze, type=_enum_name(cpp.mixture), **fields)
    return make(Aerosol, components={_enum_name(a.component): a.per_cm3 for a in cpp.amounts}, **fields)


def _from_cpp(cpp) -> Condition:
    """The Python class mirroring a typed C++ condition, its fields read back."""
    def make(cls, **fields):
        c = cls.__new__(cls)
        c.__dict__.update(fields)
        c._cpp = cpp
        return c

    if isinstance(cpp, _core.ClearAir):
        return make(Clear, visibility=cpp.visibility_m)
    if isinstance(cpp, _core.Visibility):
        return make(Visibility, distance=cpp.visibility_m)
    if isinstance(cpp, _core.GivenSigma):
        return make(Sigma, per_m=cpp.per_m)
    if isinstance(cpp, _core.RainPowerLaw):
        return make(Rain, rate=cpp.rate_mm_h, model=_enum_name(cpp.law))
    if isinstance(cpp, _core.Snow):
        return make(Snow, rate=cpp.rate_mm_h, type=_enum_name(cpp.type))
    if isinstance(cpp, _core.FogFromVisibility):
        return make(Fog, visibility=cpp.visibility_m, model=_enum_name(cpp.model), distribution=None)
    if isinstance(cpp, _core.AerosolCondition):
        return _aerosol_from_cpp(cpp, make)
    if isinstance(cpp.drops, _core.MarshallPalmerRain):
        return make(Rain, rate=cpp.drops.rate_mm_h, model="mie")
    return make(Fog, distribution=None)


def parse(text: str) -> Condition:
    """A condition from the command line's grammar, as the matching class.

    Parameters
    ----------
    text : str
        E.g. "fog:advection", "rain:8:seed", "snow:dry:4", "fog:kim:500m",
        "clear" (`grammar` gives the whole grammar).

    Returns
    -------
    Condition
        A `Rain`, `Fog`, `Snow`, ... with its fields read back.

    Raises
    ------
    ValueError
        With the command line's message and the grammar, when `text` is
        not a condition (or holds a sweep: see `expand`).

    Examples
    --------
    >>> f = parse("fog:kim:500m")
    >>> type(f).__name__, f.visibility, f.model
    ('Fog', 500.0, 'kim')
    >>> parse("snow:wet:2.5").type
    'wet'
    """
    return _from_cpp(_core.parse(text))


def expand(text: str):
    """A condition's text with its sweep expanded, one condition per value.

    Parameters
    ----------
    text : str
        A condition whose RATE, DIST or VALUE may sweep: A..B (step 1) or
        A..B/STEP, ending at B.

    Returns
    -------
    list of (str, Condition)
        The label (the text with the sweep replaced by its value) and the
        condition.

    Raises
    ------
    ValueError
        As `parse`, or for a malformed sweep.

    Examples
    --------
    >>> [label for label, c in expand("rain:1..3")]
    ['rain:1', 'rain:2', 'rain:3']
    >>> [label for label, c in expand("fog:kim:200..500/200m")]
    ['fog:kim:200m', 'fog:kim:400m', 'fog:kim:500m']
    """
    return [(label, _from_cpp(c)) for label, c in _core.expand(text)]


def grammar() -> str:
    """The condition grammar with its help text, as the command line prints it.

    Returns
    -------
    str

    Examples
    --------
    >>> print(grammar().splitlines()[0])
    conditions:
    >>> "fog:kruse|kim|naboulsi-advection|naboulsi-radiation:DIST" in grammar()
    True
    """
    return _core.grammar()


def _condition(c) -> Condition:
    if isinstance(c, Condition):
        return c
    if isinstance(c, str):
        return parse(c)
    raise TypeError(f"expected a Condition or its text, got {type(c).__name__}")


# ---- results --------------------------------------------------------------------


@dataclass(frozen=True)
class SigmaResult:
    """An extinction coefficient with its error bound and provenance.

    Attributes
    ----------
    value, error : float
        sigma and a bound on its error, in ``units``.
    units : str
        "1/m".
    model : str
        What was computed, with its source.
    convention : str
        "itu" or "seed" for the power laws, "n/a" where it does not enter.
    note : str
        Warnings, the refractive index used, the integration method.

    Examples
    --------
    >>> s = sigma("clear")
    >>> s.value, s.units, s.convention, float(s)
    (0.00015, '1/m', 'n/a', 0.00015)
    """

    value: float
    error: float
    units: str
    model: str
    convention: str
    note: str = ""

    def __float__(self) -> float:
        return self.value


@dataclass(frozen=True)
class Estimate:
    """An integral and its error bound.

    Attributes
    ----------
    value, error : float
        The integral and its error bound (the sum of the parts), 1/m for the
        coefficients (1/(m sr) for backscatter).
    parts : dict
        The error's parts: quadrature_error, tail_error, asymptotic_error,
        resonance_error, rounding_error.

    Examples
    --------
    >>> e = optics("fog:radiation", 10.6e-6).extinction
    >>> f"{e.value:.6g}", sorted(e.parts)[0]
    ('0.00193455', 'asymptotic_error')
    """

    value: float
    error: float
    parts: Dict[str, float] = field(default_factory=dict)


class Optics:
    """Bulk optical properties of a size distribution at one wavelength.

    Every field of the C++ result (weather/bulk_optics.hpp: BulkOptics) is
    an attribute and an entry of ``fields``, so a field added there appears
    here without change.

    Attributes
    ----------
    extinction, scattering, absorption : Estimate
        sigma_ext, sigma_sca, sigma_abs in 1/m.
    albedo, asymmetry : tuple of float
        (value, error) of the single-scattering albedo and of g.
    backscatter : Estimate
        beta_pi in 1/(m sr), where ``backscatter_computed``.
    lidar_ratio : tuple of float
        (value, error) in sr, where ``backscatter_computed``.
    backscatter_computed : bool
        Whether backscatter and lidar_ratio hold values (`optics` does not
        ask for them; a table with "backscatter" does).
    moments, phase : tuple of numpy.ndarray
        (values, errors) of the Legendre moments and of the phase function
        at ``angles_deg``; empty unless computed.
    angles_deg : numpy.ndarray
        The phase function's angles in degrees.
    expansion : dict
        alpha1..alpha4, beta1, beta2 -> (values, errors); empty unless computed.
    scattering_computed : bool
        False where Q_ext's large-x expansion was used (rain at short
        wavelengths): then only the extinction holds.
    evaluations, floor_panels, max_size_parameter, method
        How the integral was computed.
    m : complex
        The refractive index used.
    wavelength : float
        In metres.
    fields : dict
        All of the above by name.

    Examples
    --------
    >>> o = optics("fog:radiation", 10.6e-6)
    >>> o
    Optics(wavelength=1.06e-05 m, extinction=0.00193455 +- 2e-14 1/m, albedo=0.318505, asymmetry=0.651505)
    >>> f"{o.absorption.value:.6g}", o.scattering_computed, o.backscatter_computed
    ('0.00131839', True, False)
    """

    def __init__(self, fields: Dict[str, Any], wavelength: float):
        self.wavelength = wavelength
        self.fields = {}
        for name, value in fields.items():
            if isinstance(value, dict) and "value" in value:
                parts = {k: v for k, v in value.items() if k not in ("value", "error")}
                value = Estimate(value["value"], value["error"], parts)
            self.fields[name] = value

    def __getattr__(self, name):
        try:
            return self.__dict__["fields"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __repr__(self) -> str:
        e = self.fields["extinction"]
        return (f"Optics(wavelength={self.wavelength:g} m, extinction={e.value:.6g} +- {e.error:.2g} 1/m, "
                f"albedo={self.fields['albedo'][0]:.6g}, asymmetry={self.fields['asymmetry'][0]:.6g})")


def _settings(convention, contrast_threshold, rel_tolerance, water_table):
    return (str(convention), float(contrast_threshold), float(rel_tolerance), str(water_table))


def _distribution_index(cond: Fog, wavelength: float, water_table: str) -> complex:
    if cond.m is not None:
        return complex(cond.m)
    table = cond.water or water_table
    return complex(_core.refractive_index(table, float(wavelength)))


def sigma(condition, wavelength: float = 550e-9, *, convention: str = "itu", contrast_threshold: float = 0.02,
          rel_tolerance: float = 1e-9, water_table: str = "water") -> SigmaResult:
    """The extinction coefficient of a condition at one wavelength.

    Parameters
    ----------
    condition : Condition or str
        A condition or its text ("rain:8", "fog:advection", ...).
    wavelength : float, default 550e-9
        In metres.
    convention : {'itu', 'seed'}, default 'itu'
        How the P.1817 power laws (rain, snow) are read: dB/km as the
        Recommendation states, or 1/km as the seed paper does.
    contrast_threshold : float, default 0.02
        Koschmieder's threshold for conditions set by a visibility (0.02:
        3.912/V; 0.05: 2.996/V).
    rel_tolerance : float, default 1e-9
        Relative tolerance of the Mie size integrals.
    water_table : {'hale-querry', 'water', 'segelstein', 'ice'}, default 'water'
        The refractive-index table of Mie conditions that name none.

    Returns
    -------
    SigmaResult
        value and error in 1/m, model, convention, note.

    Raises
    ------
    ValueError
        With the command line's message: a condition outside its domain, a
        wavelength outside the water table.

    Examples
    --------
    >>> f"{sigma('rain:8').value:.6g}", f"{sigma('rain:8', convention='seed').value:.6g}"
    ('0.0010409', '0.00452058')
    >>> s = sigma("fog:advection", 1550e-9)
    >>> f"{s.value:.6g}", s.error < 1e-9 * s.value
    ('0.0295852', True)
    """
    c = _condition(condition)
    if c._cpp is None:
        o = optics(c, wavelength, rel_tolerance=rel_tolerance, water_table=water_table)
        return SigmaResult(o.extinction.value, o.extinction.error, "1/m",
                           f"Mie over {c.distribution._cpp.describe()}, m = {o.m}", "n/a")
    d = _core.sigma(c._cpp, float(wavelength), *_settings(convention, contrast_threshold, rel_tolerance, water_table))
    return SigmaResult(d["value"], d["error"], "1/m", d["model"], d["convention"], d["note"])


def optics(condition, wavelength: float = 550e-9, *, rel_tolerance: float = 1e-9, water_table: str = "water",
           m=None, contrast_threshold: float = 0.02) -> Optics:
    """Bulk optics of a Mie condition, an aerosol or a bare distribution.

    Extinction, scattering and absorption with error bounds, albedo and
    asymmetry parameter, by quadrature on the real axis.  The angular
    quantities cost O(x^2) per sphere and are not computed here
    (``backscatter_computed`` is False, ``moments`` and ``phase`` are
    empty): `table` with the quantities "backscatter", "lidar_ratio" or
    "phase" (at ``angles=``) gives them; the Legendre moments come from the
    command line, ``attenuvis optics --moments L`` or ``attenuvis table
    --quantities moments:L``.

    Parameters
    ----------
    condition : Condition, str or Distribution
        A Mie condition (a Fog preset or distribution, Rain(model="mie"),
        drops:...), an aerosol (`Haze`, `Aerosol`; the external mixture of
        its components) or a bare Distribution.
    wavelength : float, default 550e-9
        In metres.
    rel_tolerance : float, default 1e-9
        Relative tolerance of the size integrals.
    water_table : {'hale-querry', 'water', 'segelstein', 'ice'}, default 'water'
        The refractive-index table where the condition names none.
    m : complex, optional
        With a bare Distribution: its refractive index (default: the water table's).
    contrast_threshold : float, default 0.02
        Koschmieder's threshold, for an aerosol scaled to a visibility.

    Returns
    -------
    Optics

    Raises
    ------
    ValueError
        For a condition that is not a Mie condition, or the command line's
        message.

    Examples
    --------
    >>> o = optics(LogNormal(1e8, 4e-6, 1.5), 10.6e-6, m=1.2 + 0.05j)
    >>> f"{o.extinction.value:.6g}", f"{o.albedo[0]:.4f}", o.m
    ('0.00842883', '0.6132', (1.2+0.05j))
    """
    if isinstance(condition, Distribution):
        condition = Fog(distribution=condition, m=m)
    c = _condition(condition)
    if c._cpp is None:
        index = _distribution_index(c, wavelength, water_table)
        d = _core.distribution_optics(c.distribution._cpp, float(wavelength), index, float(rel_tolerance))
        return Optics(d, float(wavelength))
    if not _core.needs_mie(c._cpp):
        raise ValueError(f"{c.text}: bulk optics need a Mie condition (fog preset or distribution, rain model "
                         "'mie') or an aerosol (Haze, Aerosol)")
    if isinstance(c._cpp, _core.AerosolCondition):
        d = _core.aerosol_optics(c._cpp, float(wavelength), float(rel_tolerance), float(contrast_threshold))
        return Optics(d, float(wavelength))
    d = _core.condition_optics(c._cpp, float(wavelength), float(rel_tolerance), str(water_table))
    return Optics(d, float(wavelength))


# The phase function's angles when "phase" is asked for without ``angles``:
# every degree, as the command line's table (a fog's forward peak needs a
# finer grid near 0).
DEFAULT_PHASE_ANGLES = tuple(float(a) for a in range(181))
PHASE_NORMALISATION = "int p dOmega = 4 pi (isotropic p = 1; divide by 4 pi for 1/sr)"


@dataclass
class Table:
    """sigma and other quantities over conditions x wavelengths.

    Attributes
    ----------
    labels : sequence of str
        The conditions' text (sweeps expanded).
    wavelengths : numpy.ndarray
        In metres.
    value, error : numpy.ndarray
        sigma and its error bound, (conditions, wavelengths), 1/m.
    models : sequence of str
        What each condition computes.
    quantities : dict
        Every other quantity asked for, by name -> (conditions, wavelengths)
        array, NaN where a condition has no bulk optics (it is not a Mie
        condition, or rain's large-x expansion left no Q_sca).  With
        "phase": "phase" and "phase_error", (conditions, wavelengths,
        angles) arrays of the bulk phase function, normalised int p dOmega
        = 4 pi, and its error.
    angles : numpy.ndarray or None
        The phase function's angles in degrees, with "phase".

    Examples
    --------
    >>> t = table(["clear", "rain:1..2"], [550e-9, 1550e-9])
    >>> t.labels, t.value.shape
    (['clear', 'rain:1', 'rain:2'], (3, 2))
    """

    labels: Sequence[str]
    wavelengths: np.ndarray
    value: np.ndarray
    error: np.ndarray
    models: Sequence[str]
    quantities: Dict[str, np.ndarray] = field(default_factory=dict)
    angles: Optional[np.ndarray] = None
    _cpp: Any = field(default=None, repr=False, compare=False)

    def _write(self, path, format: str, layer_thickness_m: float = 1000.0) -> None:
        if self._cpp is None:
            raise ValueError(f"{format}: only a table made by table() can be written")
        from ._version import __version__
        self._cpp.write(os.fspath(path), format, float(layer_thickness_m), f"attenuvis {__version__} (Python)")

    def to_libradtran(self, path) -> None:
        """Write the netCDF Mie table libRadtran's uvspec reads (wc_file / ic_file).

        The layout of libRadtran's ``mie`` tool: one effective radius per
        condition (on an equidistant grid, as uvspec interpolates in it),
        ``ext`` in km^-1 per g/m^3, ``pmom`` with the factor 2l+1, the phase
        function rebuilt from the moments (docs/guide/optics-tables.md).

        Parameters
        ----------
        path : str or os.PathLike
            Written whole or not at all.

        Raises
        ------
        ValueError, RuntimeError
            Without ``moments`` in `table`, for conditions that are not Mie
            conditions, radii not equidistant, or several refractive indices
            at one wavelength: the message says what to change.

        Examples
        --------
        >>> t = table(["fog:radiation"], [1.55e-6], ["sigma", "albedo"], moments=16)  # doctest: +SKIP
        >>> t.to_libradtran("water.mie.cdf")  # doctest: +SKIP
        """
        self._write(path, "libradtran")

    def to_disort(self, path, layer_thickness: float = 1000.0) -> None:
        """Write DTAUC, SSALB and PMOM (chi_l, PMOM(0) = 1) per cell as text.

        Parameters
        ----------
        path : str or os.PathLike
        layer_thickness : float, default 1000
            In metres: DTAUC = sigma_ext x layer_thickness.

        Raises
        ------
        ValueError, RuntimeError
            As `to_libradtran`.
        """
        self._write(path, "disort", layer_thickness)

    def to_xarray(self):
        """The table as an xarray Dataset.

        Returns
        -------
        xarray.Dataset
            "sigma", "sigma_error" and every other quantity over (condition,
            wavelength), "model" over condition; with "phase", "phase" and
            "phase_error" over (condition, wavelength, angle).

        Raises
        ------
        ImportError
            Without xarray (Debian's python3-xarray); the package imports
            without it.

        Examples
        --------
        >>> ds = table(["clear"], [550e-9]).to_xarray()  # doctest: +SKIP
        >>> ds.sigma.attrs["units"]  # doctest: +SKIP
        '1/m'
        """
        import xarray as xr  # optional: the package imports without it

        coords = {"condition": list(self.labels), "wavelength": ("wavelength", self.wavelengths, {"units": "m"})}
        phase = {}
        if self.angles is not None:
            coords["angle"] = ("angle", self.angles, {"units": "degree", "long_name": "scattering angle"})
            dims = ("condition", "wavelength", "angle")
            phase = {"phase": (dims, self.quantities["phase"], {"units": "1", "long_name": "bulk phase function, "
                                                                 + PHASE_NORMALISATION}),
                     "phase_error": (dims, self.quantities["phase_error"], {"units": "1"})}
        return xr.Dataset(
            {
                "sigma": (("condition", "wavelength"), self.value, {"units": "1/m", "long_name": "extinction coefficient"}),
                "sigma_error": (("condition", "wavelength"), self.error, {"units": "1/m"}),
                "model": (("condition",), list(self.models)),
                **{name: (("condition", "wavelength"), v, {"units": _TABLE_QUANTITIES[name]["units"]})
                   for name, v in self.quantities.items() if name in _TABLE_QUANTITIES},
                **phase,
            },
            coords=coords,
        )


def _table_pairs(conditions):
    """(label, C++ condition) for every condition, sweeps in text expanded."""
    if isinstance(conditions, (str, Condition)):
        conditions = [conditions]
    pairs = []
    for c in conditions:
        if isinstance(c, str):
            pairs.extend((label, p._cpp) for label, p in expand(c))
        else:
            c = _condition(c)
            if c._cpp is None:
                raise TypeError("table(): a Fog(distribution=...) has no C++ condition; use sigma() per wavelength")
            pairs.append((c.text, c._cpp))
    return pairs


def table(conditions, wavelengths, quantities: Sequence[str] = ("sigma",), *, convention: str = "itu",
          contrast_threshold: float = 0.02, rel_tolerance: float = 1e-9, water_table: str = "water",
          threads: int = 0, angles=None, moments: int = -1) -> Table:
    """sigma and other quantities for every condition at every wavelength.

    The cells are computed in parallel (the C++ table, weather/sigma_table.hpp)
    without the GIL; Ctrl-C interrupts them.

    Parameters
    ----------
    conditions : Condition, str or sequence of them
        Text may sweep: "rain:1..10".
    wavelengths : array_like of float
        In metres.
    quantities : sequence of {'sigma', 'scattering', 'absorption', 'albedo', 'asymmetry', 'backscatter', \
'lidar_ratio', 'phase'}, default ('sigma',)
        sigma always; the bulk optics of Mie conditions by the names of
        `Optics` (registry("table_quantities") gives their units); "phase":
        the bulk phase function (int p dOmega = 4 pi) with its error at
        ``angles``.
    convention, contrast_threshold, rel_tolerance, water_table
        As for `sigma`.
    threads : int, default 0
        Worker threads (0: every core); the numbers do not depend on it.
    angles : array_like of float, optional
        With "phase": the scattering angles in degrees, increasing, in [0,
        180]; default `DEFAULT_PHASE_ANGLES` (every degree).
    moments : int, default -1
        >= 0: also the Legendre moments chi_0..chi_L of the phase function
        of every Mie cell (L = moments), which `Table.to_libradtran` and
        `Table.to_disort` need.

    Returns
    -------
    Table
        ``.to_xarray()`` gives an xarray Dataset; ``.to_libradtran(path)``
        and ``.to_disort(path)`` the radiative-transfer inputs.

    Raises
    ------
    ValueError
        For an unknown quantity, angles without "phase", a bad angle grid,
        or the command line's message for a condition.
    TypeError
        For a Fog(distribution=...), which has no C++ condition.

    Examples
    --------
    >>> t = table(["clear", "fog:radiation"], [10.6e-6], ["sigma", "albedo"])
    >>> t.labels, [f"{v:.6g}" for v in t.value[:, 0]]
    (['clear', 'fog:radiation'], ['0.00015', '0.00193455'])
    >>> [f"{v:.6g}" for v in t.quantities["albedo"][:, 0]]  # clear air has no bulk optics
    ['nan', '0.318505']
    """
    phase = "phase" in quantities
    extra = list(dict.fromkeys(q for q in quantities if q not in ("sigma", "phase")))
    for q in extra:
        if q not in _TABLE_QUANTITIES:
            known = ", ".join(name for name in _TABLE_QUANTITIES if name != "sigma")
            raise ValueError(f"unknown quantity {q!r}: sigma, phase, {known}")
    if angles is not None and not phase:
        raise ValueError("angles set the phase function's angles: add \"phase\" to quantities")
    angle_list = [float(a) for a in np.asarray(DEFAULT_PHASE_ANGLES if angles is None else angles,
                                               dtype=np.float64).reshape(-1)] if phase else []
    pairs = _table_pairs(conditions)
    w = np.asarray(wavelengths, dtype=np.float64).reshape(-1)
    names = [_TABLE_QUANTITIES[q]["name"] for q in ["sigma", *extra]]
    (values, errors, models, p, p_error), cpp = _core.table(pairs, list(w), *_settings(convention, contrast_threshold,
                                                                                     rel_tolerance, water_table),
                                                          int(threads), names, angle_list, int(moments))
    more = {q: values[_TABLE_QUANTITIES[q]["name"]] for q in extra}
    if phase:
        more["phase"], more["phase_error"] = p, p_error
    sigma_ext = _TABLE_QUANTITIES["sigma"]["name"]
    return Table([c[0] for c in pairs], w, values[sigma_ext], errors[sigma_ext], models, more,
                 np.asarray(angle_list, dtype=np.float64) if phase else None, cpp)


def refractive_index(wavelength, table: str = "water"):
    """The complex refractive index n + ik of water or ice from a table.

    Interpolated in ln(lambda): n linearly, ln k linearly (weather/refractive_index.hpp).

    Parameters
    ----------
    wavelength : array_like of float
        In metres, any shape.
    table : {'hale-querry', 'water', 'segelstein', 'ice'}, default 'water'
        registry("water_tables") gives each table's range and source ("water"
        is "hale-querry"); a table's file name ("water-segelstein-1981") is
        accepted too.

    Returns
    -------
    numpy.ndarray of complex
        The shape of `wavelength`.

    Raises
    ------
    ValueError
        For an unknown table, or a wavelength outside it.

    Examples
    --------
    >>> m = refractive_index([550e-9, 10.6e-6])
    >>> [f"{z.real:.4f}+{z.imag:.3g}i" for z in m]
    ['1.3330+1.96e-09i', '1.1785+0.0715i']
    """
    w = np.asarray(wavelength, dtype=np.float64)
    out = np.array([_core.refractive_index(table, float(v)) for v in w.reshape(-1)], dtype=np.complex128)
    return out.reshape(w.shape)
