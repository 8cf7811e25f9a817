"""sigma and bulk optics of a user log-normal fog over 400-1600 nm, into an
xarray Dataset and a netCDF file.

    /usr/bin/python3 examples/fog_optics.py OUTDIR
"""
import sys

import numpy as np
import xarray as xr

from attenuvis import weather as w

out = sys.argv[1]
# 200 drops per cm^3, median radius 5 um, geometric width 1.6.
fog = w.Fog(distribution=w.LogNormal(number_per_m3=200e6, median_radius_m=5e-6, sigma_g=1.6))
wavelengths = np.linspace(400e-9, 1600e-9, 13)
rows = [w.optics(fog, lam, rel_tolerance=1e-6) for lam in wavelengths]
ds = xr.Dataset(
    {
        "sigma_ext": ("wavelength", [o.extinction.value for o in rows], {"units": "1/m"}),
        "sigma_ext_error": ("wavelength", [o.extinction.error for o in rows], {"units": "1/m"}),
        "sigma_sca": ("wavelength", [o.scattering.value for o in rows], {"units": "1/m"}),
        "albedo": ("wavelength", [o.albedo[0] for o in rows]),
        "asymmetry": ("wavelength", [o.asymmetry[0] for o in rows]),
        "m_real": ("wavelength", [o.m.real for o in rows]),
        "m_imag": ("wavelength", [o.m.imag for o in rows]),
    },
    coords={"wavelength": ("wavelength", wavelengths, {"units": "m"})},
    attrs={"distribution": repr(fog.distribution), "index": "water, Hale & Querry (1973)"},
)
ds.to_netcdf(f"{out}/fog_optics.nc")
print(ds)
