"""The examples run, so they cannot rot: each writes its files into a fresh
directory."""

import subprocess
import sys

import numpy as np
import pytest


def run(source_dir, tmp_path, name, *args):
    subprocess.run([sys.executable, str(source_dir / "examples" / name), str(tmp_path), *args], check=True,
                   timeout=600, env={**__import__("os").environ, "MPLBACKEND": "Agg"})


def test_seed_figures(source_dir, tmp_path):
    run(source_dir, tmp_path, "seed_figures.py", "2.0")
    assert (tmp_path / "seed_heatmaps.png").stat().st_size > 10000
    scores = np.load(tmp_path / "layout0_sum.npy")
    assert scores.shape[0] == 4
    # Clear air sees farthest: its S_S is the largest at every node.
    assert np.all(scores[0] >= scores[1:])


def test_fog_optics(source_dir, tmp_path):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("netCDF4")
    run(source_dir, tmp_path, "fog_optics.py")
    ds = xr.open_dataset(tmp_path / "fog_optics.nc")
    assert ds.sigma_ext.shape == (13,) and np.all(ds.sigma_ext > 0)
    # The file holds what the library computes.
    from attenuvis import weather as w
    fog = w.LogNormal(number_per_m3=200e6, median_radius_m=5e-6, sigma_g=1.6)
    o = w.optics(fog, float(ds.wavelength[3]), rel_tolerance=1e-6)
    assert float(ds.sigma_ext[3]) == o.extinction.value and float(ds.sigma_ext_error[3]) == o.extinction.error


def test_city_weather(source_dir, tmp_path):
    run(source_dir, tmp_path, "city_weather.py")
    assert (tmp_path / "city_weather.png").stat().st_size > 10000
    (npy,) = tmp_path.glob("node_*_distances.npy")
    d = np.load(npy)
    assert d.ndim == 1 and len(d) > 0 and np.all(d > 0)
