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
    Rain(8)                      P.1817-1-style power law, model "seed" | "carbonneau" | "p1814"
    Rain(8, model="mie")         Mie over Marshall-Palmer drops
    Snow(4, type="dry")          P.1817-1 snow, type "dry" | "wet"
    Fog("advection")             Mie over the P.1817-1 / seed preset ("advection" | "radiation")
    Fog(visibility=500, model="kim")   empirical fog (kruse, kim, naboulsi-advection, naboulsi-radiation)
    Fog(distribution=LogNormal(...), m=1.33+1e-8j)   Mie over your own drops

``parse("fog:advection")`` reads the command line's grammar (``grammar()``).
Power laws are read per the ``convention`` argument ("itu", the default, or
"seed"; README, units).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np

from . import _attenuvis

_core = _attenuvis.weather

__all__ = [
    "Condition", "Clear", "Visibility", "Sigma", "Rain", "Snow", "Fog",
    "Distribution", "LogNormal", "ModifiedGamma", "Gamma", "MarshallPalmer", "GunnMarshall", "PowerLaw",
    "preset", "tabulated",
    "parse", "expand", "grammar", "sigma", "optics", "table", "refractive_index",
    "SigmaResult", "Estimate", "Optics", "Table",
]

# ---- size distributions -----------------------------------------------------

_RADIUS_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}
# number per volume of air per radius, in m^-4
_DENSITY_UNITS = {"m^-4": 1.0, "cm^-3 um^-1": 1e12, "m^-3 um^-1": 1e6, "m^-3 mm^-1": 1e3}


class Distribution:
    """A particle size distribution n(r) = dN/dr (SI inside: r in m, n in m^-4).

    Build one with LogNormal, ModifiedGamma, Gamma, MarshallPalmer,
    GunnMarshall, PowerLaw, preset(name) or tabulated(radius, density).
    """

    def __init__(self, cpp):
        self._cpp = cpp

    def density(self, radius_m):
        """n(r) in m^-4 at radii in metres (array in, array out)."""
        r = np.asarray(radius_m, dtype=np.float64)
        return self._cpp.density(r.reshape(-1)).reshape(r.shape)

    def moment(self, p: float) -> float:
        """Integral of r^p n(r) dr over all r (SI)."""
        return self._cpp.moment(float(p))

    def moments(self, bulk_density_kg_m3: float = 1000.0) -> Dict[str, float]:
        """number_per_m3, water_content_kg_m3, effective_radius_m, mode_radius_m, mean_radius_m."""
        return self._cpp.moments(float(bulk_density_kg_m3))

    def scaled(self, factor: float) -> "Distribution":
        return Distribution(self._cpp.scaled(float(factor)))

    def to_number(self, number_per_m3: float) -> "Distribution":
        """The same shape rescaled to ``number_per_m3`` particles per m^3."""
        return Distribution(self._cpp.normalised_to_number(float(number_per_m3)))

    def to_water_content(self, kg_per_m3: float, bulk_density_kg_m3: float = 1000.0) -> "Distribution":
        """The same shape rescaled to a liquid (or ice) water content in kg/m^3."""
        return Distribution(self._cpp.normalised_to_water_content(float(kg_per_m3), float(bulk_density_kg_m3)))

    def __repr__(self) -> str:
        return f"Distribution({self._cpp.describe()})"


def LogNormal(number_per_m3: float, median_radius_m: float, sigma_g: float) -> Distribution:
    """n = N / (sqrt(2 pi) ln(sg) r) exp(-(ln r - ln rg)^2 / (2 ln^2 sg)); sigma_g > 1 is the geometric width."""
    return Distribution(_core.SizeDistribution.log_normal(number_per_m3, median_radius_m, sigma_g))


def ModifiedGamma(a: float, alpha: float, b: float, gamma: float = 1.0) -> Distribution:
    """n = a r^alpha exp(-b r^gamma) in the P.1817-1 / seed units: r in um, n in cm^-3 um^-1 (Deirmendjian 1969)."""
    return Distribution(_core.SizeDistribution.modified_gamma_um(a, alpha, b, gamma))


def Gamma(number_per_m3: float, alpha: float, mode_radius_m: float) -> Distribution:
    """A gamma distribution of ``number_per_m3`` particles, shape alpha, mode radius in metres."""
    return Distribution(_core.SizeDistribution.gamma(number_per_m3, alpha, mode_radius_m))


def MarshallPalmer(rate_mm_h: float) -> Distribution:
    """Rain drops, Marshall & Palmer (1948): N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1."""
    return Distribution(_core.SizeDistribution.marshall_palmer(rate_mm_h))


def GunnMarshall(rate_mm_h: float) -> Distribution:
    """Snow, Gunn & Marshall (1958), R the melted precipitation rate in mm/h."""
    return Distribution(_core.SizeDistribution.gunn_marshall(rate_mm_h))


def PowerLaw(c_si: float, nu: float, r_min_m: float, r_max_m: float) -> Distribution:
    """Junge: n = c r^-nu (SI) on [r_min_m, r_max_m]."""
    return Distribution(_core.SizeDistribution.power_law(c_si, nu, r_min_m, r_max_m))


def preset(name: str) -> Distribution:
    """A named distribution: "advection", "radiation" (P.1817-1 / seed fogs), "marshall-palmer:R", "gunn-marshall:R"."""
    return Distribution(_core.SizeDistribution.preset(name))


def tabulated(radius, density, *, radius_unit: str = "um", density_unit: str = "cm^-3 um^-1",
              source: str = "arrays") -> Distribution:
    """A piecewise-linear n(r) through the points (radius, density), zero outside.

    radius_unit: "m", "mm", "um" or "nm"; density_unit (number per volume per
    radius): "m^-4", "cm^-3 um^-1", "m^-3 um^-1" or "m^-3 mm^-1".
    Radii must increase; densities be >= 0 (ValueError names the index).
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
    """A weather condition; ``text`` is the command line's spelling of it."""

    _cpp: Any = None  # the typed C++ condition, or None for a Python-only one

    @property
    def text(self) -> str:
        return _core.to_text(self._cpp)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.text!r})"


class Clear(Condition):
    """Clear air: the seed paper's sigma = 1.5e-4 1/m, or Koschmieder from ``visibility`` (m)."""

    def __init__(self, visibility: Optional[float] = None):
        self.visibility = visibility
        self._cpp = _core.ClearAir(None if visibility is None else float(visibility))


class Visibility(Condition):
    """Any atmosphere of meteorological visibility ``distance`` (m), Koschmieder."""

    def __init__(self, distance: float):
        self.distance = float(distance)
        self._cpp = _core.Visibility(self.distance)


class Sigma(Condition):
    """A given extinction coefficient, 1/m."""

    def __init__(self, per_m: float):
        self.per_m = float(per_m)
        self._cpp = _core.GivenSigma(self.per_m)


def _index_source(m, water):
    if m is not None and water is not None:
        raise TypeError("give m= or water=, not both")
    if m is not None:
        return _core.ConstantIndex(complex(m))
    if water is not None:
        tables = {"hale-querry": "hale_querry", "water": "hale_querry", "segelstein": "segelstein", "ice": "ice"}
        if water not in tables:
            raise ValueError(f"water must be one of {sorted(tables)}, not {water!r}")
        return getattr(_core.WaterTable, tables[water])
    return _core.SettingsWaterTable()


def _rescaling(number_density, lwc):
    if number_density is not None and lwc is not None:
        raise TypeError("give number_density= or lwc=, not both")
    if number_density is not None:
        return _core.NumberDensity(float(number_density))
    if lwc is not None:
        return _core.LiquidWaterContent(float(lwc))
    return _core.AsGiven()


class Rain(Condition):
    """Rain at ``rate`` mm/h.  model: "seed" (default), "carbonneau", "p1814"
    (P.1817-1-style power laws, read per the convention), or "mie" (Mie over
    Marshall-Palmer drops; m=, water= choose the index)."""

    def __init__(self, rate: float, model: str = "seed", *, m=None, water=None):
        self.rate = float(rate)
        self.model = model
        if model == "mie":
            self._cpp = _core.MieCondition(_core.MarshallPalmerRain(self.rate), _index_source(m, water), _core.AsGiven())
        else:
            laws = {"seed": _core.RainLaw.seed, "carbonneau": _core.RainLaw.carbonneau, "p1814": _core.RainLaw.p1814}
            if model not in laws:
                raise ValueError(f"rain model must be one of seed, carbonneau, p1814, mie, not {model!r}")
            if m is not None or water is not None:
                raise TypeError("m= and water= apply to model='mie' only")
            self._cpp = _core.RainPowerLaw(self.rate, laws[model])


class Snow(Condition):
    """Snow at ``rate`` mm/h (melted), ``type`` "dry" or "wet" (P.1817-1)."""

    def __init__(self, rate: float, type: str = "dry"):
        self.rate = float(rate)
        self.type = type
        if type not in ("dry", "wet"):
            raise ValueError(f"snow type must be 'dry' or 'wet', not {type!r}")
        self._cpp = _core.Snow(getattr(_core.SnowType, type), self.rate)


class Fog(Condition):
    """Fog, three ways:

    * ``Fog("advection")`` / ``Fog("radiation")``: Mie over the P.1817-1 /
      seed preset drops; ``m=`` (complex) or ``water=`` ("hale-querry",
      "segelstein", "ice") choose the index (default: the settings' water
      table); ``number_density=`` (cm^-3) or ``lwc=`` (g/m^3) rescale.
    * ``Fog(visibility=500, model="kim")``: empirical model from a
      visibility in metres (kruse, kim, naboulsi-advection, naboulsi-radiation).
    * ``Fog(distribution=LogNormal(...), m=...)``: Mie over your own drops
      (index from m=, else the water table at each wavelength).
    """

    def __init__(self, preset: Optional[str] = None, *, visibility: Optional[float] = None, model: str = "kim",
                 distribution: Optional[Distribution] = None, m=None, water=None,
                 number_density: Optional[float] = None, lwc: Optional[float] = None, file: Optional[str] = None):
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
            models = {"kruse": "kruse", "kim": "kim", "naboulsi-advection": "naboulsi_advection",
                      "naboulsi-radiation": "naboulsi_radiation"}
            if model not in models:
                raise ValueError(f"fog model must be one of {sorted(models)}, not {model!r}")
            self._cpp = _core.FogFromVisibility(getattr(_core.VisibilityFogModel, models[model]), float(visibility))
        else:
            if file is not None:
                drops = _core.DistributionFile(str(file))
            elif preset in ("advection", "radiation"):
                drops = getattr(_core.FogPreset, preset)
            else:
                raise ValueError(f"fog preset must be 'advection' or 'radiation', not {preset!r}")
            self._cpp = _core.MieCondition(drops, _index_source(m, water), _rescaling(number_density, lwc))

    @property
    def text(self) -> str:
        if self._cpp is None:
            return f"fog:distribution({self.distribution._cpp.describe()})"
        return _core.to_text(self._cpp)


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
        return make(Rain, rate=cpp.rate_mm_h, model=cpp.law.name)
    if isinstance(cpp, _core.Snow):
        return make(Snow, rate=cpp.rate_mm_h, type=cpp.type.name)
    if isinstance(cpp, _core.FogFromVisibility):
        return make(Fog, visibility=cpp.visibility_m, model=cpp.model.name.replace("_", "-"), distribution=None)
    if isinstance(cpp.drops, _core.MarshallPalmerRain):
        return make(Rain, rate=cpp.drops.rate_mm_h, model="mie")
    return make(Fog, distribution=None)


def parse(text: str) -> Condition:
    """A condition from the command line's grammar, e.g. "fog:advection", "rain:8:seed",
    "snow:dry:4", "fog:kim:500m", "clear", as the matching class (Rain, Fog, ...).
    ValueError (with the grammar) when it is not one."""
    return _from_cpp(_core.parse(text))


def expand(text: str):
    """A list with sweeps expanded: "rain:1..3" -> [("rain:1", Rain), ("rain:2", Rain), ...]."""
    return [(label, _from_cpp(c)) for label, c in _core.expand(text)]


def grammar() -> str:
    """The condition grammar with its help text."""
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
    """An extinction coefficient: value and error bound in ``units`` (1/m), the
    model and its source, the power-law convention ("itu", "seed" or "n/a")."""

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
    """An integral and its error bound (sum of its parts, in ``parts``), 1/m."""

    value: float
    error: float
    parts: Dict[str, float] = field(default_factory=dict)


class Optics:
    """Bulk optical properties of a size distribution at one wavelength.

    extinction, scattering, absorption: Estimate (1/m); albedo, asymmetry:
    (value, error); m: the refractive index used; fields: every field the
    library reports (names as in weather/bulk_optics.hpp), so fields added
    there appear here without change.
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
    """Extinction coefficient of ``condition`` (a Condition or its text) at
    ``wavelength`` (m).  Returns SigmaResult(value, error, units="1/m", model,
    convention).  Mie conditions integrate to ``rel_tolerance``; power laws
    are read per ``convention`` ("itu" or "seed"); Koschmieder uses
    ``contrast_threshold`` (0.02 or 0.05).  Errors: ValueError with the
    command line's message."""
    c = _condition(condition)
    if c._cpp is None:
        o = optics(c, wavelength, rel_tolerance=rel_tolerance, water_table=water_table)
        return SigmaResult(o.extinction.value, o.extinction.error, "1/m",
                           f"Mie over {c.distribution._cpp.describe()}, m = {o.m}", "n/a")
    d = _core.sigma(c._cpp, float(wavelength), *_settings(convention, contrast_threshold, rel_tolerance, water_table))
    return SigmaResult(d["value"], d["error"], "1/m", d["model"], d["convention"], d["note"])


def optics(condition, wavelength: float = 550e-9, *, rel_tolerance: float = 1e-9, water_table: str = "water",
           m=None) -> Optics:
    """Bulk optics (extinction, scattering, absorption with error bounds,
    albedo, asymmetry) of a Mie condition (Fog preset or distribution,
    Rain(model="mie")) or of a bare Distribution (then give ``m``, or the
    water table is used) at ``wavelength`` (m)."""
    if isinstance(condition, Distribution):
        condition = Fog(distribution=condition, m=m)
    c = _condition(condition)
    if c._cpp is None:
        index = _distribution_index(c, wavelength, water_table)
        d = _core.distribution_optics(c.distribution._cpp, float(wavelength), index, float(rel_tolerance))
        return Optics(d, float(wavelength))
    if not _core.needs_mie(c._cpp):
        raise ValueError(f"{c.text}: bulk optics need a Mie condition (fog preset or distribution, rain model 'mie')")
    d = _core.condition_optics(c._cpp, float(wavelength), float(rel_tolerance), str(water_table))
    return Optics(d, float(wavelength))


# Bulk-optics quantities a table can hold besides sigma: name -> (unit, how to
# read it from Optics).  Add a line here when BulkOptics gains a field.
_OPTICS_QUANTITIES = {
    "scattering": ("1/m", lambda o: o.scattering.value),
    "absorption": ("1/m", lambda o: o.absorption.value),
    "albedo": ("1", lambda o: o.albedo[0]),
    "asymmetry": ("1", lambda o: o.asymmetry[0]),
}


# The phase function's angles when "phase" is asked for without ``angles``:
# every degree, as the command line's table (a fog's forward peak needs a
# finer grid near 0).
DEFAULT_PHASE_ANGLES = tuple(float(a) for a in range(181))
PHASE_NORMALISATION = "int p dOmega = 4 pi (isotropic p = 1; divide by 4 pi for 1/sr)"


@dataclass
class Table:
    """sigma over conditions x wavelengths: ``value`` and ``error`` are
    (conditions, wavelengths) arrays in 1/m; ``labels`` and ``models`` name
    the conditions; ``quantities`` holds any other quantity asked for
    (name -> (conditions, wavelengths) array; NaN where a condition has no
    bulk optics, i.e. is not a Mie condition).  With "phase": ``angles``
    (degrees) and quantities "phase" and "phase_error", (conditions,
    wavelengths, angles) arrays of the bulk phase function, normalised
    int p dOmega = 4 pi, and its error estimate."""

    labels: Sequence[str]
    wavelengths: np.ndarray
    value: np.ndarray
    error: np.ndarray
    models: Sequence[str]
    quantities: Dict[str, np.ndarray] = field(default_factory=dict)
    angles: Optional[np.ndarray] = None

    def to_xarray(self):
        """An xarray.Dataset (sigma, sigma_error over condition x wavelength);
        needs Debian's python3-xarray."""
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
                **{name: (("condition", "wavelength"), v, {"units": _OPTICS_QUANTITIES[name][0]})
                   for name, v in self.quantities.items() if name in _OPTICS_QUANTITIES},
                **phase,
            },
            coords=coords,
        )


def table(conditions, wavelengths, quantities: Sequence[str] = ("sigma",), *, convention: str = "itu",
          contrast_threshold: float = 0.02, rel_tolerance: float = 1e-9, water_table: str = "water",
          threads: int = 0, angles=None) -> Table:
    """sigma for every condition (Condition objects or text; text may sweep,
    "rain:1..10") at every wavelength (m), computed in parallel without the
    GIL.  ``quantities`` may add bulk optics: "scattering", "absorption"
    (1/m), "albedo", "asymmetry" (computed cell by cell, Mie conditions
    only), and "phase": the bulk phase function (int p dOmega = 4 pi) with
    its error at ``angles`` (degrees, increasing, in [0, 180]; default
    DEFAULT_PHASE_ANGLES, every degree), computed with sigma in parallel.
    Returns a Table; ``.to_xarray()`` gives an xarray Dataset."""
    phase = "phase" in quantities
    extra = [q for q in quantities if q not in ("sigma", "phase")]
    for q in extra:
        if q not in _OPTICS_QUANTITIES:
            raise ValueError(f"unknown quantity {q!r}: sigma, phase, {', '.join(_OPTICS_QUANTITIES)}")
    if angles is not None and not phase:
        raise ValueError("angles set the phase function's angles: add \"phase\" to quantities")
    angle_list = [float(a) for a in np.asarray(DEFAULT_PHASE_ANGLES if angles is None else angles,
                                               dtype=np.float64).reshape(-1)] if phase else []
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
    w = np.asarray(wavelengths, dtype=np.float64).reshape(-1)
    value, error, models, p, p_error = _core.table(pairs, list(w), *_settings(convention, contrast_threshold,
                                                                              rel_tolerance, water_table),
                                                   int(threads), angle_list)
    more = {q: np.full(value.shape, np.nan) for q in extra}
    for i, (label, cpp) in enumerate(pairs):
        if not extra or not _core.needs_mie(cpp):
            continue
        for j, lam in enumerate(w):
            o = Optics(_core.condition_optics(cpp, float(lam), float(rel_tolerance), str(water_table)), float(lam))
            for q in extra:
                more[q][i, j] = _OPTICS_QUANTITIES[q][1](o)
    if phase:
        more["phase"], more["phase_error"] = p, p_error
    return Table([c[0] for c in pairs], w, value, error, models, more,
                 np.asarray(angle_list, dtype=np.float64) if phase else None)


def refractive_index(wavelength, table: str = "water"):
    """Complex index n + ik of "water" (Hale & Querry 1973), "segelstein" (1981)
    or "ice" (Warren & Brandt 2008) at ``wavelength`` (m), array in, array out."""
    w = np.asarray(wavelength, dtype=np.float64)
    out = np.array([_core.refractive_index(table, float(v)) for v in w.reshape(-1)], dtype=np.complex128)
    return out.reshape(w.shape)
