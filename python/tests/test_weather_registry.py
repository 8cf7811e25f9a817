"""The Python layer names exactly what the C++ registries name (weather/registry.hpp):
its lookups, the bound enums, the choices its docstrings list and the fields
of Optics.  A name added to (or dropped from) a registry, or written into the
Python layer by hand, fails here until both sides agree."""

import inspect
import re

import pytest

from attenuvis import weather as w
from attenuvis import _weather_names as wn  # the registries' name tables the public functions check against

KINDS = ["water_tables", "fog_presets", "distribution_presets", "rain_power_laws", "snow_types",
         "visibility_fog_models", "table_quantities", "aerosol_components", "aerosol_mixtures", "humidity_rules"]


def names(kind, aliases=False):
    out = set()
    for entry in w.registry(kind):
        out.add(entry["name"])
        if aliases:
            out.update(entry.get("aliases", []))
    return out


def documented_choices(obj, parameter):
    """The quoted names of a numpy-style ``parameter : {'a', 'b'}`` line of obj's docstring."""
    for line in inspect.getdoc(obj).splitlines():
        m = re.match(rf"{parameter} : (?:sequence of )?\{{([^}}]*)\}}", line.strip())
        if m:
            return set(re.findall(r"'([^']*)'", m.group(1)))
    raise AssertionError(f"{obj.__name__}'s docstring lists no choices for {parameter}")


def test_every_kind_is_listed_with_its_fields():
    assert w.registry_kinds() == KINDS
    for kind in KINDS:
        entries = w.registry(kind)
        assert entries, kind
        for e in entries:
            assert {"name", "units", "help", "citation"} <= set(e), (kind, e)
            assert e["name"] and e["help"], (kind, e)
    with pytest.raises(ValueError, match="water_tables"):
        w.registry("colours")


def test_python_lookups_are_the_registries():
    assert set(wn._WATER_TABLES) == names("water_tables", aliases=True)
    assert set(wn._FOG_PRESETS) == names("fog_presets")
    assert set(wn._FOG_MODELS) == names("visibility_fog_models")
    assert set(wn._RAIN_LAWS) == names("rain_power_laws")
    assert set(wn._SNOW_TYPES) == names("snow_types")
    assert set(wn._TABLE_QUANTITIES) == {e["python_name"] for e in w.registry("table_quantities")}
    assert set(wn._AEROSOL_COMPONENTS) == names("aerosol_components")
    assert set(wn._AEROSOL_MIXTURES) == names("aerosol_mixtures")
    assert set(wn._HUMIDITY_RULES) == names("humidity_rules")


@pytest.mark.parametrize("enum,kind", [(wn._core.RainLaw, "rain_power_laws"), (wn._core.SnowType, "snow_types"),
                                       (wn._core.VisibilityFogModel, "visibility_fog_models"),
                                       (wn._core.FogPreset, "fog_presets"), (wn._core.WaterTable, "water_tables"),
                                       (wn._core.AerosolComponent, "aerosol_components"),
                                       (wn._core.AerosolMixture, "aerosol_mixtures"),
                                       (wn._core.HumidityRule, "humidity_rules")])
def test_bound_enums_are_the_registries(enum, kind):
    assert set(enum.__members__) == {n.replace("-", "_") for n in names(kind)}


@pytest.mark.parametrize("obj,parameter,kind,extra", [
    (w.Rain, "model", "rain_power_laws", {"mie"}),
    (w.Rain, "water", "water_tables", set()),
    (w.Snow, "type", "snow_types", set()),
    (w.Fog, "preset", "fog_presets", set()),
    (w.Fog, "model", "visibility_fog_models", set()),
    (w.Fog, "water", "water_tables", set()),
    (w.preset, "name", "distribution_presets", set()),
    (w.sigma, "water_table", "water_tables", set()),
    (w.optics, "water_table", "water_tables", set()),
    (w.refractive_index, "table", "water_tables", set()),
    (w.Haze, "type", "aerosol_mixtures", set()),
    (w.Haze, "growth", "humidity_rules", set()),
    (w.Aerosol, "growth", "humidity_rules", set()),
])
def test_documented_choices_are_the_registries(obj, parameter, kind, extra):
    assert documented_choices(obj, parameter) == names(kind, aliases=True) | extra


def test_documented_table_quantities_are_the_registry():
    python_names = {e["python_name"] for e in w.registry("table_quantities")}
    assert documented_choices(w.table, "quantities") == python_names | {"phase"}


def test_every_registry_name_is_accepted_and_reads_back():
    for law in names("rain_power_laws"):
        assert w.parse(w.Rain(8, model=law).text).model == law
    for kind in names("snow_types"):
        assert w.parse(w.Snow(2, kind).text).type == kind
    for model in names("visibility_fog_models"):
        assert w.parse(w.Fog(visibility=500, model=model).text).model == model
    for table in names("water_tables", aliases=True):
        text = w.Fog("advection", water=table).text
        assert w.parse(text).text == text
    for fog in names("fog_presets"):
        assert w.Fog(fog).text == "fog:" + fog
    for mixture in names("aerosol_mixtures"):
        assert w.parse(w.Haze(mixture, rh=50).text).type == mixture
    for rule in names("humidity_rules"):
        assert w.parse(w.Haze("urban", rh=85, growth=rule).text).growth == rule
    for component in names("aerosol_components"):
        assert w.parse(w.Aerosol({component: 3}, rh=0).text).components == {component: 3.0}
    for name in names("distribution_presets"):
        assert w.preset(name.replace(":R", ":2")).moment(0) > 0
    t = w.table(["clear"], [550e-9], [e["python_name"] for e in w.registry("table_quantities")])
    assert set(t.quantities) == {e["python_name"] for e in w.registry("table_quantities")} - {"sigma"}


def test_optics_shows_and_documents_every_field():
    fields = set(w.optics("fog:radiation", 10.6e-6).fields) - {"m", "index_source"}
    documented = set()
    section = False
    for line in inspect.getdoc(w.Optics).splitlines():
        if line.strip() in ("Attributes", "Examples"):
            section = line.strip() == "Attributes"
            continue
        m = re.match(r"([a-z_, ]+) :", line) if section else None
        if m:
            documented.update(n.strip() for n in m.group(1).split(","))
        elif section and line and not line.startswith(" ") and not line.startswith("-"):
            documented.update(n.strip() for n in line.split(","))
    assert fields == documented - {"m", "wavelength", "fields"}
