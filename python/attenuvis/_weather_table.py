"""Tables over conditions and wavelengths, their files, and refractive indices.

Part of attenuvis.weather (its public names are re-exported there)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import _attenuvis

from ._weather_names import (_TABLE_QUANTITIES)
from ._weather_conditions import (Condition, _condition, expand)
from ._weather_optics import _settings

_core = _attenuvis.weather

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
