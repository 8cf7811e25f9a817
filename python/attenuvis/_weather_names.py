"""The names of the C++ registries: kinds, entries, enum conversions.

Part of attenuvis.weather (its public names are re-exported there)."""

from __future__ import annotations

from typing import Any, Dict, List

from . import _attenuvis

_core = _attenuvis.weather


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
