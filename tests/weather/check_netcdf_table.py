#!/usr/bin/env python3
"""A netCDF sigma table read back against the CSV of the same table.

Runs `attenuvis table` twice on the same conditions and wavelengths (CSV and
netCDF-4), then checks with Debian's python3-netcdf4 and python3-xarray that
  - the CSV reads as is with csv.DictReader and pandas (header line first),
  - every value of every quantity, its error, the Legendre moments and the
    parameter coordinates is
    the same double in both files (CSV numbers are shortest round-trip text),
    and a missing CSV cell is a NaN _FillValue in netCDF and back,
  - the CF layout: Conventions, units, long_name, standard_name,
    ancillary_variables, coordinates, global attributes;
and, on a second pair of tables, that every value and error of the phase
function on its angle dimension is the CSV's.
Usage: check_netcdf_table.py ATTENUVIS_PROGRAM WORK_DIR
"""
import csv
import math
import os
import subprocess
import sys

import netCDF4
import pandas
import xarray

QUANTITIES = ["sigma_ext", "sigma_sca", "sigma_abs", "ssa", "g", "backscatter", "lidar_ratio"]
COEFFICIENTS = {"sigma_ext", "sigma_sca", "sigma_abs"}
# Units in a --units km table (netCDF UDUNITS text) and the CSV column suffix.
UNITS = {"backscatter": ("km-1 sr-1", "_per_km_sr"), "lidar_ratio": ("sr", "_sr")}
MOMENTS = 3  # chi_0..chi_3 on the netCDF dimension "moment"
# The phase function on the netCDF dimension "angle", on a table of its own: radiation fog in the infrared
# (size parameters below ~50: a second or two) beside a power law, with moments to share the file.
ANGLES = [0.0, 0.5, 45.0, 90.0, 135.0, 180.0]
PHASE_CONDITIONS = "fog:radiation,rain:8"
PHASE_WAVELENGTHS = "1550nm,10600nm"
# Mie (fog preset), a swept power law, an empirical fog set by a visibility, a given sigma.
CONDITIONS = "fog:advection:m=1.33+0.001i,rain:1..100/50,fog:kim:500m,sigma:2/km"
WAVELENGTHS = "550nm,1550nm"

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def run_table(program, out, fmt, conditions=CONDITIONS, wavelengths=WAVELENGTHS,
              quantities=",".join(QUANTITIES + ["moments:%d" % MOMENTS]), extra=()):
    args = [program, "table", "--conditions", conditions, "--wavelengths", wavelengths, "--quantities",
            quantities, "--units", "km", "--format", fmt, "--out", out, "--threads", "2"] + list(extra)
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("attenuvis table failed (%s): %s %s" % (" ".join(args), r.stdout, r.stderr))


def same(csv_text, nc_value, what):
    if csv_text == "":
        check(math.isnan(nc_value), "%s: empty in CSV, %r in netCDF" % (what, nc_value))
    else:
        check(float(csv_text) == nc_value, "%s: CSV %s, netCDF %r" % (what, csv_text, nc_value))


def check_phase_table(program, work):
    """The phase function: CSV columns phase_<angle>deg and their errors against the netCDF variable
    phase_function(wavelength, condition, angle) and phase_function_error, value by value."""
    csv_path, nc_path = os.path.join(work, "phase.csv"), os.path.join(work, "phase.nc")
    for p in (csv_path, csv_path + ".meta.json", nc_path):
        if os.path.exists(p):
            os.remove(p)
    extra = ["--angles", ",".join("%g" % a for a in ANGLES)]
    for path, fmt in ((csv_path, "csv"), (nc_path, "netcdf")):
        run_table(program, path, fmt, PHASE_CONDITIONS, PHASE_WAVELENGTHS, "g,moments:2,phase", extra)
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 2 * 2, "phase CSV rows: %d, expected 4" % len(rows))
    nc = netCDF4.Dataset(nc_path)
    nc.set_auto_mask(False)
    check(list(nc.dimensions) == ["wavelength", "condition", "moment", "angle"],
          "phase table dimensions %s" % list(nc.dimensions))
    # The phase function: a CF coordinate variable "angle" and the field with its error companion.
    check(list(nc["angle"][:]) == ANGLES, "angle coordinate %s" % list(nc["angle"][:]))
    check(nc["angle"].units == "degree" and nc["angle"].long_name == "scattering angle", "angle attributes")
    p, pe = nc["phase_function"], nc["phase_function_error"]
    check(p.dimensions == ("wavelength", "condition", "angle") and pe.dimensions == p.dimensions,
          "phase_function dimensions %s" % (p.dimensions,))
    check(p.units == "1" and pe.units == "1", "phase_function units")
    check("int p dOmega = 4 pi" in p.long_name, "phase_function long_name names the normalisation: %s" % p.long_name)
    check(p.ancillary_variables == "phase_function_error", "phase_function ancillary_variables")
    check("condition_label" in p.coordinates and "rate" in p.coordinates, "phase_function coordinates")
    check(math.isnan(p._FillValue) and math.isnan(pe._FillValue), "phase_function _FillValue NaN")
    wavelengths, labels = list(nc["wavelength"][:]), list(nc["condition_label"][:])
    compared = 0
    for row in rows:
        w, c = wavelengths.index(float(row["wavelength_nm"])), labels.index(row["condition"])
        mie = row["condition"] == "fog:radiation"
        for i, a in enumerate(ANGLES):
            column = "phase_%sdeg" % ("%g" % a)
            same(row[column], p[w, c, i], "%s %s %s" % (column, row["wavelength_nm"], row["condition"]))
            same(row[column + "_error"], pe[w, c, i], "%s_error %s %s" % (column, row["wavelength_nm"], row["condition"]))
            check((row[column] != "") == mie, "phase present only for the Mie condition: %s" % row["condition"])
            compared += 2
    nc.close()
    ds = xarray.open_dataset(nc_path)  # angle as a coordinate: select by degrees
    fog90 = [r for r in rows if r["wavelength_nm"] == "10600" and r["condition"] == "fog:radiation"][0]["phase_90deg"]
    check(float(ds["phase_function"].sel(wavelength=10600.0, angle=90.0).isel(condition=0)) == float(fog90),
          "xarray value of phase_function at 90 deg, 10.6 um")
    ds.close()
    return compared


def main():
    program, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    csv_path, nc_path = os.path.join(work, "table.csv"), os.path.join(work, "table.nc")
    for p in (csv_path, csv_path + ".meta.json", nc_path):
        if os.path.exists(p):
            os.remove(p)
    run_table(program, csv_path, "csv")
    run_table(program, nc_path, "netcdf")

    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    frame = pandas.read_csv(csv_path)
    check(len(frame) == len(rows) == 2 * 6, "CSV rows: %d (pandas %d), expected 12" % (len(rows), len(frame)))
    check(str(frame["sigma_ext_per_km"].dtype) == "float64", "pandas reads sigma_ext_per_km as numbers")

    nc = netCDF4.Dataset(nc_path)
    nc.set_auto_mask(False)  # missing values stay NaN (their _FillValue), as the CSV's empty cells
    check(nc.getncattr("Conventions") == "CF-1.8", "global Conventions")
    for attr in ("title", "unit_convention", "refractive_index_source", "method", "mie_rel_tolerance",
                 "attenuvis_version", "missing_values"):
        check(attr in nc.ncattrs(), "global attribute " + attr)
    check(nc.getncattr("unit_convention") == "itu", "unit convention itu")
    check(list(nc.dimensions) == ["wavelength", "condition", "moment"], "dimensions %s" % list(nc.dimensions))
    check(list(nc["moment"][:]) == list(range(MOMENTS + 1)), "moment coordinate")
    check(nc["chi"].dimensions == ("wavelength", "condition", "moment"), "chi dimensions")
    wavelengths = nc["wavelength"][:]
    labels = list(nc["condition_label"][:])
    check(nc["wavelength"].units == "nm" and nc["wavelength"].standard_name == "radiation_wavelength",
          "wavelength coordinate attributes")
    check(labels == ["fog:advection:m=1.33+0.001i", "rain:1", "rain:51", "rain:100", "fog:kim:500m", "sigma:2/km"],
          "condition labels %s" % labels)

    for q in QUANTITIES:
        v, e = nc[q], nc[q + "_error"]
        units = "km-1" if q in COEFFICIENTS else UNITS[q][0] if q in UNITS else "1"
        check(v.units == units and e.units == units, "%s units %s" % (q, v.units))
        check(v.dimensions == ("wavelength", "condition"), "%s dimensions" % q)
        check(bool(v.long_name), "%s long_name" % q)
        check(v.ancillary_variables == q + "_error", "%s ancillary_variables" % q)
        check("condition_label" in v.coordinates and "rate" in v.coordinates, "%s coordinates" % q)
        # CF's aerosol coefficients exclude cloud droplets: no aerosol standard_name on fog and rain, and
        # the coefficients say why.
        check("aerosol" not in getattr(v, "standard_name", ""), "%s standard_name" % q)
        if q in COEFFICIENTS:
            check("cloud droplets" in v.comment, "%s comment on its standard name" % q)

    compared = 0
    for row in rows:
        w = [i for i, x in enumerate(wavelengths) if x == float(row["wavelength_nm"])]
        c = [i for i, x in enumerate(labels) if x == row["condition"]]
        check(len(w) == 1 and len(c) == 1, "row %s found once in netCDF" % row)
        if len(w) != 1 or len(c) != 1:
            continue
        w, c = w[0], c[0]
        for q in QUANTITIES:
            suffix = "_per_km" if q in COEFFICIENTS else UNITS[q][1] if q in UNITS else ""
            same(row[q + suffix], nc[q][w, c], "%s %s %s" % (q, row["wavelength_nm"], row["condition"]))
            same(row[q + "_error" + suffix], nc[q + "_error"][w, c], "%s_error %s" % (q, row["condition"]))
            compared += 2
        for l in range(MOMENTS + 1):
            same(row["chi_%d" % l], nc["chi"][w, c, l], "chi_%d %s" % (l, row["condition"]))
            same(row["chi_%d_error" % l], nc["chi_error"][w, c, l], "chi_%d_error %s" % (l, row["condition"]))
            compared += 2
        same(row["koschmieder_visibility_m"], nc["koschmieder_visibility"][w, c], "visibility " + row["condition"])
        same(row["rate_mm_h"], nc["rate"][c], "rate " + row["condition"])
        same(row["visibility_m"], nc["visibility"][c], "visibility parameter " + row["condition"])
        same(row["given_sigma_per_km"], nc["given_sigma"][c], "given sigma " + row["condition"])
        check(row["convention"] == nc["convention"][c], "convention " + row["condition"])
        compared += 5
    # The rule for missing values: only the Mie condition has sigma_sca, ssa, g; every condition has sigma_ext.
    for row in rows:
        mie = row["condition"].startswith("fog:advection")
        check((row["ssa"] != "") == mie, "ssa present only for the Mie condition: %s" % row["condition"])
        check((row["chi_0"] != "") == mie, "moments present only for the Mie condition: %s" % row["condition"])
        if mie:
            check(float(row["chi_0"]) == 1.0 or abs(float(row["chi_0"]) - 1) <= float(row["chi_0_error"]) + 1e-15,
                  "chi_0 = 1: %s" % row["chi_0"])
        check(row["sigma_ext_per_km"] != "", "sigma_ext present: %s" % row["condition"])
    # The swept rates as a numeric coordinate, ending at B.
    check([x for x in nc["rate"][:] if not math.isnan(x)] == [1.0, 51.0, 100.0], "rate coordinate %s" % nc["rate"][:])
    nc.close()

    ds = xarray.open_dataset(nc_path)  # CF decoding: _FillValue, coordinates
    check("rate" in ds["sigma_ext"].coords, "xarray sees rate as a coordinate of sigma_ext")
    check(float(ds["sigma_ext"].sel(wavelength=550.0).isel(condition=0)) ==
          float([r for r in rows if r["wavelength_nm"] == "550" and r["condition"].startswith("fog:adv")][0]["sigma_ext_per_km"]),
          "xarray value of sigma_ext at 550 nm")
    ds.close()

    compared += check_phase_table(program, work)

    if failures:
        print("FAILED (%d):" % len(failures))
        for f in failures:
            print("  " + f)
        sys.exit(1)
    print("netCDF and CSV agree: %d values compared, CF attributes present" % compared)


if __name__ == "__main__":
    main()
