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

from ._weather_names import registry, registry_kinds
from ._weather_distributions import (
    Distribution, Gamma, GunnMarshall, LogNormal, MarshallPalmer, ModifiedGamma, PowerLaw, preset, tabulated
)
from ._weather_conditions import (
    Aerosol, Clear, Condition, Fog, Haze, Rain, Sigma, Snow, Visibility, expand, grammar, parse
)
from ._weather_optics import Estimate, Optics, SigmaResult, optics, sigma
from ._weather_table import Table, refractive_index, table
from . import _weather_table

# Constants of tables (in the stub, not in __all__): the default phase angles
# and the phase function's normalisation.
DEFAULT_PHASE_ANGLES = _weather_table.DEFAULT_PHASE_ANGLES
PHASE_NORMALISATION = _weather_table.PHASE_NORMALISATION

__all__ = [
    "Condition", "Clear", "Visibility", "Sigma", "Rain", "Snow", "Fog", "Haze", "Aerosol",
    "Distribution", "LogNormal", "ModifiedGamma", "Gamma", "MarshallPalmer", "GunnMarshall", "PowerLaw",
    "preset", "tabulated",
    "parse", "expand", "grammar", "sigma", "optics", "table", "refractive_index",
    "registry", "registry_kinds",
    "SigmaResult", "Estimate", "Optics", "Table",
]

# The definitions live in the private modules above; they are documented,
# printed and pickled as this module's own.
for _name in __all__:
    globals()[_name].__module__ = __name__
del _name

