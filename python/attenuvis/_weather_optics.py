"""Extinction and bulk optics of one condition: sigma() and optics().

Part of attenuvis.weather (its public names are re-exported there)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict

from . import _attenuvis

from ._weather_distributions import (Distribution)
from ._weather_conditions import (Fog, _condition)

_core = _attenuvis.weather


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
    shortfall : str
        Empty when the requested tolerance was met; else which integral
        missed it and by how much (``error`` is then the error reached).

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
    shortfall: str = ""

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
    evaluations, resonances_located, resonances_resolved, max_size_parameter, method
        How the integral was computed.
    shortfall : str
        Empty when every quantity met its tolerance; else (nearly lossless
        particles beyond the evaluation budget) which quantity missed it and
        by how much.  The reported errors are then the ones reached.
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
                           f"Mie over {c.distribution._cpp.describe()}, m = {o.m}", "n/a", shortfall=o.shortfall)
    d = _core.sigma(c._cpp, float(wavelength), *_settings(convention, contrast_threshold, rel_tolerance, water_table))
    return SigmaResult(d["value"], d["error"], "1/m", d["model"], d["convention"], d["note"], d["shortfall"])


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
