"""Weather conditions: the typed conditions, the grammar, conversion from C++.

Part of attenuvis.weather (its public names are re-exported there)."""

from __future__ import annotations

from typing import Any, Dict, Optional

from . import _attenuvis

from ._weather_names import (
    _AEROSOL_COMPONENTS, _AEROSOL_MIXTURES, _FOG_MODELS, _FOG_PRESETS, _HUMIDITY_RULES, _RAIN_LAWS,
    _SNOW_TYPES, _WATER_TABLES, _at_most_one, _enum_name, _enum_value
)
from ._weather_distributions import Distribution

_core = _attenuvis.weather


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
