#!/usr/bin/env python3
"""The libRadtran and DISORT tables read back as their readers read them.

Runs `attenuvis table` on the same drops and wavelengths as CSV, as a
libRadtran Mie table (--format libradtran) and as DISORT text, then, with
Debian's python3-netcdf4, applies the rules of uvspec's reader of
wc_properties files (libRadtran libsrc_c/miecalc.c, read_mie_table):
  - the global attribute "version" is there (several wavelengths per file),
    the dimensions nmommax, nreff, nphamat (1, 4 or 6), nthetamax;
  - wavelen in micrometres (uvspec multiplies by 1000 to nm), reff
    equidistant as floats ((float)(reff[i-1] + dr) == (float)reff[i]);
  - nmom < nmommax for every cell (else uvspec stops: "nstr larger than the
    number of moments"); pmom divided by 2l + 1 gives chi_l;
  - theta starts at 180 degrees;
and compares with the CSV:
  - chi_l = pmom / (2l + 1) against the CSV's chi_l (pmom is float: 1e-6),
  - ext x lwc (km^-1 / (g/m^3) times g/m^3) against sigma_ext in 1/km and
    lwc against `attenuvis distribution` of the same drops,
  - ssa against the CSV's ssa,
  - the phase function rebuilt from the moments, p = sum (2l+1) chi_l
    P_l(cos theta), against the CSV's bulk phase function on its angles,
    for drops whose moments are complete (every |(2l+1) chi_l| < 1e-5 beyond
    nmom), within the CSV's error plus the float rounding of the file;
and the DISORT text: DTAUC = sigma_ext x thickness, SSALB = ssa, PMOM = chi.
A table whose effective radii are not equidistant, or without moments, must
be refused with a message and no file.
Usage: check_libradtran_table.py ATTENUVIS_PROGRAM WORK_DIR
"""
import csv
import math
import os
import subprocess
import sys

import netCDF4
import numpy

# Gamma drops, n ~ r^6 exp(-6 r / r_mode): r_eff = 1.5 r_mode, so 1, 1.5, 2 um give an equidistant
# r_eff of 1.5, 2.25, 3 um.  At 10.6 um (x < 20) 40 moments are complete; at 1.55 um they are not.
CONDITIONS = ",".join("drops:gamma:r=%gum:alpha=6:lwc=0.2" % r for r in (1, 1.5, 2))
WAVELENGTHS = "1550nm,10600nm"
L = 40
ANGLES = "0:180:5"

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def run(program, *args, ok=True):
    r = subprocess.run([program, *args], capture_output=True, text=True)
    if ok and r.returncode != 0:
        sys.exit("attenuvis %s failed: %s %s" % (" ".join(args), r.stdout, r.stderr))
    return r


def table(program, out, fmt, conditions=CONDITIONS, quantities="sigma_ext,ssa,moments:%d,phase" % L, extra=(),
          ok=True):
    angles = ("--angles", ANGLES) if "phase" in quantities else ()
    return run(program, "table", "--conditions", conditions, "--wavelengths", WAVELENGTHS, "--quantities",
               quantities, *angles, "--units", "km", "--format", fmt, "--out", out, *extra, ok=ok)


def legendre(l_max, mu):
    p = [1.0, mu]
    for l in range(1, l_max):
        p.append(((2 * l + 1) * mu * p[l] - l * p[l - 1]) / (l + 1))
    return p[: l_max + 1]


def main():
    program, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    csv_path, cdf_path, disort_path = (os.path.join(work, n) for n in ("t.csv", "water.mie.cdf", "t.disort"))
    table(program, csv_path, "csv")
    table(program, cdf_path, "libradtran")
    table(program, disort_path, "disort", extra=("--layer-thickness", "250m"))
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    by_key = {(float(r["wavelength_nm"]), r["condition"]): r for r in rows}

    d = netCDF4.Dataset(cdf_path)
    check(d.file_format == "NETCDF3_CLASSIC", "libRadtran's mie tool writes classic netCDF: %s" % d.file_format)
    check("version" in d.ncattrs(), "no global attribute version: uvspec would read one wavelength only")
    for dim in ("nmommax", "nreff", "nphamat", "nthetamax", "nlam"):
        check(dim in d.dimensions, "dimension %s missing" % dim)
    check(len(d.dimensions["nphamat"]) in (1, 4, 6), "nphamat must be 1, 4 or 6")
    nmommax = len(d.dimensions["nmommax"])
    wavelen_nm = d["wavelen"][:] * 1000.0
    reff = d["reff"][:]
    dr = reff[1] - reff[0]
    for i in range(1, len(reff)):
        check(numpy.float32(reff[i - 1] + dr) == numpy.float32(reff[i]), "reff not equidistant at %d: %r" % (i, reff))
    labels = d.getncattr("size_distr").split(": ", 1)[1].split("; ")
    lwc = d["lwc"][:]
    for j, label in enumerate(labels):  # each condition rescales its drops to lwc=0.2 g/m^3
        check(abs(lwc[j] - 0.2) <= 1e-9 * 0.2, "lwc of %s: %r, the condition asks 0.2 g/m^3" % (label, lwc[j]))
    for w, lam in enumerate(wavelen_nm):
        for j, label in enumerate(labels):
            row = by_key[(round(float(lam), 6), label)]
            where = "%s at %g nm" % (label, lam)
            nmom = int(d["nmom"][w, j, 0])
            check(nmom < nmommax, "%s: nmom %d >= nmommax %d (uvspec refuses)" % (where, nmom, nmommax))
            check(float(d["theta"][w, j, 0, 0]) == 180.0, "%s: theta does not start at 180" % where)
            # ext per mass times the water content: sigma_ext in 1/km.
            sigma = float(row["sigma_ext_per_km"])
            ext = float(d["ext"][w, j]) * float(lwc[j])
            check(abs(ext - sigma) <= 1e-12 * sigma, "%s: ext x lwc %r, CSV sigma_ext %r 1/km" % (where, ext, sigma))
            check(abs(float(d["ssa"][w, j]) - float(row["ssa"])) <= 1e-15, "%s: ssa differs from the CSV" % where)
            # uvspec's rule: pmom / (2l + 1); float storage, 1e-6 relative; the writers divide by chi_0
            # (1 but for rounding), as libRadtran's mie tool does.
            chi = [float(d["pmom"][w, j, 0, l]) / (2 * l + 1) for l in range(L + 1)]
            chi0 = float(row["chi_0"])
            for l in range(L + 1):
                ref = float(row["chi_%d" % l]) / chi0
                check(abs(chi[l] - ref) <= 1e-6 * max(abs(ref), 1e-6),
                      "%s: chi_%d from pmom %r, CSV %r" % (where, l, chi[l], ref))
            # The phase function rebuilt from the moments where they are complete.
            complete = nmom <= L and all(abs((2 * l + 1) * chi[l]) < 1e-5 for l in range(nmom, L + 1))
            if not complete:
                continue
            for theta in range(0, 181, 5):
                mu = math.cos(math.radians(theta))
                p = sum((2 * l + 1) * c * pl for l, (c, pl) in enumerate(zip(chi, legendre(L, mu))))
                ref = float(row["phase_%ddeg" % theta])
                err = float(row["phase_%ddeg_error" % theta])
                # float pmom: 6e-8 of each term; the terms beyond L are below the completeness test's 1e-5.
                rounding = 6e-8 * sum((2 * l + 1) * abs(c) for l, c in enumerate(chi))
                check(abs(p - ref) <= err + rounding, "%s: p(%d) from the moments %r, CSV %r +- %r"
                      % (where, theta, p, ref, err))
    d.close()

    # DISORT: one line per cell.
    with open(disort_path) as f:
        lines = [l.split() for l in f if not l.startswith("#")]
    check(len(lines) == len(rows), "disort: %d lines for %d cells" % (len(lines), len(rows)))
    for fields in lines:
        row = by_key[(float(fields[0]), fields[1])]
        dtauc, ssalb, n = float(fields[2]), float(fields[3]), int(fields[4])
        check(abs(dtauc - float(row["sigma_ext_per_km"]) * 0.25) <= 1e-12 * dtauc, "disort DTAUC of %s" % fields[:2])
        check(ssalb == float(row["ssa"]), "disort SSALB of %s" % fields[:2])
        check(n == L and float(fields[5]) == 1.0, "disort NMOM/PMOM(0) of %s" % fields[:2])
        chi0 = float(row["chi_0"])
        for l in range(L + 1):
            ref = float(row["chi_%d" % l]) / chi0
            check(abs(float(fields[5 + l]) - ref) <= 1e-15 * max(abs(ref), 1e-300), "disort PMOM(%d) of %s" % (l, fields[:2]))

    # Refusals: no file, a message that says what to change.
    bad = os.path.join(work, "bad.mie.cdf")
    r = table(program, bad, "libradtran", conditions="drops:gamma:r=1um:alpha=6:lwc=0.2,"
              "drops:gamma:r=1.2um:alpha=6:lwc=0.2,drops:gamma:r=2um:alpha=6:lwc=0.2", ok=False)
    check(r.returncode != 0 and "equidistant" in r.stderr and not os.path.exists(bad),
          "uneven effective radii: %r" % r.stderr)
    r = table(program, bad, "libradtran", quantities="sigma_ext,ssa", ok=False)
    check(r.returncode != 0 and "moments:L" in r.stderr and not os.path.exists(bad), "no moments: %r" % r.stderr)

    if failures:
        print("\n".join(failures[:40]))
        sys.exit("%d checks failed" % len(failures))
    print("libRadtran and DISORT tables read back as uvspec and DISORT read them")


main()
