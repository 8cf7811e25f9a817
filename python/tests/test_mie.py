"""attenuvis.mie against published values, the C++ single-call API and the
command line, and its NumPy handling (broadcasting, dtypes, strides, empty
arrays, bad elements)."""

import csv
import json
import math
import subprocess

import numpy as np
import pytest

import attenuvis
from attenuvis import mie

core = attenuvis._attenuvis.mie


def published(source_dir, name):
    with open(source_dir / "tests" / "data" / "mie" / name) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def half_unit(text):
    """Half a unit in the last printed digit of a published number."""
    mantissa = text.lower().split("e")[0]
    exponent = int(text.lower().split("e")[1]) if "e" in text.lower() else 0
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (exponent - decimals)


def test_bohren_huffman_appendix_a():
    # Bohren & Huffman (1983), Appendix A, p. 482: BHMIE for radius 0.525 um,
    # m = 1.55, wavelength 0.6328 um (x = 5.2128); printed QSCA = QEXT = 3.10543,
    # QBACK = 2.92534 (tests/data/mie/bohren_huffman_appendix_a.csv; the same
    # numbers the C++ test tests/mie/test_mie_published.cpp checks).
    q = mie.efficiencies(m=1.55, radius=0.525e-6, wavelength=0.6328e-6)
    assert abs(q.qext - 3.10543) <= half_unit("3.10543")
    assert abs(q.qsca - 3.10543) <= half_unit("3.10543")
    assert abs(q.qback - 2.92534) <= half_unit("2.92534")
    same = mie.efficiencies(2 * math.pi * 0.525 / 0.6328, 1.55)
    assert same.qext == pytest.approx(q.qext, rel=1e-13)  # x differs by rounding of 2 pi r / lambda


def test_bohren_huffman_scattering_matrix(source_dir):
    # The appendix's table: S11/S11(0), -S12/S11, S33/S11, S34/S11, 6 digits.
    # Entries the single-precision program printed wrong in the last digit carry
    # the documented tolerance of tests/data/mie/documented_inaccuracies.csv
    # (the list the C++ test uses).
    documented = {(r["row"], r["field"]): float(r["rel"])
                  for r in published(source_dir, "documented_inaccuracies.csv") if r["source"] == "bh"}
    rows = published(source_dir, "bohren_huffman_appendix_a.csv")
    angles = np.array([float(r["angle_deg"]) for r in rows])
    sm = mie.scattering_matrix(2 * math.pi * 0.525 / 0.6328, 1.55, angles)
    for i, r in enumerate(rows):
        for got, key in ((sm.s11[i] / sm.s11[0], "s11"), (-sm.s12[i] / sm.s11[i], "pol"),
                         (sm.s33[i] / sm.s11[i], "s33"), (sm.s34[i] / sm.s11[i], "s34")):
            tol = max(half_unit(r[key]), documented.get((r["angle_deg"], key), 0.0) * abs(float(r[key])))
            assert abs(got - float(r[key])) <= tol, (r["angle_deg"], key, got, r[key])


def test_wiscombe_1979_appendix_broadcast(source_dir):
    # Wiscombe (1979) NCAR/TN-140, Appendix: m = 1.5 and 1.5 + 0.1i at x = 10..5000,
    # seven digits; all eight spheres in one broadcast call (x down, m across).
    rows = published(source_dir, "wiscombe_1979_appendix.csv")
    x = np.array(sorted({float(r["x"]) for r in rows}))[:, None]
    m = np.array([1.5, 1.5 + 0.1j])[None, :]
    q = mie.efficiencies(x, m)
    assert q.qext.shape == (4, 2)
    for r in rows:
        i = int(np.flatnonzero(x[:, 0] == float(r["x"]))[0])
        j = 0 if float(r["k"]) == 0 else 1
        for key in ("qext", "qsca", "qabs", "g"):
            assert abs(getattr(q, key)[i, j] - float(r[key])) <= half_unit(r[key]), (r, key)


def test_same_as_single_call_api():
    rng = np.random.default_rng(1)
    x = rng.uniform(0.1, 200, 300)
    m = rng.uniform(1.0, 2.0, 300) + 1j * rng.uniform(0, 0.5, 300)
    q = mie.efficiencies(x, m)
    for i in range(0, 300, 7):
        ref = core.sphere(float(x[i]), complex(m[i]))
        got = [q.qext[i], q.qsca[i], q.qabs[i], q.qback[i], q.qpr[i], q.g[i], q.terms[i]]
        assert got == list(ref)  # bit for bit: spheres() is sphere() in lanes


def test_same_as_command_line(cli, tmp_path):
    x = np.array([0.5, 3.0, 42.0])
    m = np.array([1.33 + 1e-8j, 1.55, 1.5 + 0.1j])
    text = "".join(f"{a!r} {b.real!r} {b.imag!r}\n" for a, b in zip(x, m))
    out = subprocess.run([cli, "mie"], input=text, capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(out.splitlines()))
    q = mie.efficiencies(x, m)
    for i, r in enumerate(rows):
        for key in ("qext", "qsca", "qabs", "qback", "g"):
            assert float(r[key]) == getattr(q, key)[i]  # 17 digits round-trip


@pytest.mark.parametrize("xshape,mshape,shape", [((), (), ()), ((5,), (), (5,)), ((5,), (5,), (5,)),
                                                 ((4, 1), (3,), (4, 3)), ((2, 3, 4), (1, 4), (2, 3, 4))])
def test_broadcasting_shapes(xshape, mshape, shape):
    x = np.full(xshape, 2.0)
    m = np.full(mshape, 1.33 + 0.01j)
    q = mie.efficiencies(x, m)
    for a in q:
        assert a.shape == shape
    assert q.terms.dtype == np.int64 and q.qext.dtype == np.float64
    assert np.all(q.qext == mie.efficiencies(2.0, 1.33 + 0.01j).qext)


def test_float32_and_non_contiguous_inputs():
    base = np.linspace(0.1, 100, 2001)
    ref = mie.efficiencies(base[::2], 1.33 + 1e-8j)
    strided = mie.efficiencies(base[::2], 1.33 + 1e-8j)  # a view with stride 16 bytes
    assert not base[::2].flags.c_contiguous
    np.testing.assert_array_equal(strided.qext, ref.qext)
    f32 = base[::2].astype(np.float32)
    m32 = np.float32(1.33)  # 1.33000004291534423828125 exactly
    q32 = mie.efficiencies(f32, m32)
    np.testing.assert_array_equal(q32.qext, mie.efficiencies(f32.astype(np.float64), float(m32)).qext)
    # Fortran-ordered 2-D x with a per-column m.
    xf = np.asfortranarray(base[:2000].reshape(40, 50))
    mm = np.linspace(1.2, 1.6, 50) + 0.001j
    qf = mie.efficiencies(xf, mm)
    assert qf.qext[7, 9] == core.sphere(float(xf[7, 9]), complex(mm[9]))[0]
    # Integer x.
    assert mie.efficiencies(np.array([3]), 1.5).qext[0] == mie.efficiencies(3.0, 1.5).qext


def test_empty_arrays():
    q = mie.efficiencies(np.empty((0,)), 1.33)
    assert all(a.shape == (0,) for a in q)
    q = mie.efficiencies(np.empty((3, 0)), np.empty((0,), dtype=complex))
    assert q.qext.shape == (3, 0)


def test_bad_elements_raise_with_their_index():
    x = np.array([1.0, 2.0, -3.0, 4.0])
    with pytest.raises(ValueError, match=r"element 2: .*x"):
        mie.efficiencies(x, 1.33)
    with pytest.raises(ValueError, match=r"element 1 \(index \(0, 1\)\): .*refractive index.* \(and 1 more bad elements\)"):
        mie.efficiencies(np.ones((2, 3)), np.array([1.5, 1.5 - 0.1j, 1.5]))
    q = mie.efficiencies(x, 1.33, errors="nan")
    assert np.isnan(q.qext[2]) and np.isfinite(q.qext[[0, 1, 3]]).all()
    assert q.qext[3] == mie.efficiencies(4.0, 1.33).qext
    with pytest.raises(ValueError, match="errors must be"):
        mie.efficiencies(1.0, 1.33, errors="ignore")
    with pytest.raises(ValueError, match="shape mismatch|broadcast"):
        mie.efficiencies(np.ones(3), np.ones(4))
    with pytest.raises(TypeError):
        mie.efficiencies(1.0 + 1j, 1.33)
    with pytest.raises(ValueError):
        mie.amplitudes(0.0, 1.33, [0.0])


def test_thread_count_independence():
    x = np.random.default_rng(2).uniform(0.1, 300, 5000)
    one = mie.efficiencies(x, 1.33 + 1e-8j, threads=1)
    many = mie.efficiencies(x, 1.33 + 1e-8j, threads=3)
    for a, b in zip(one, many):
        np.testing.assert_array_equal(a, b)


def test_medium_index():
    # x = 2 pi r n_medium / lambda: a sphere in water.
    a = mie.efficiencies(m=1.2, radius=1e-6, wavelength=0.5e-6, medium_index=1.33)
    b = mie.efficiencies(2 * np.pi * 1e-6 * 1.33 / 0.5e-6, 1.2)
    assert a.qext == b.qext


def test_amplitudes_and_optical_theorem():
    x, m = 10.0, 1.5 + 0.1j
    s1, s2 = mie.amplitudes(x, m, np.array([[0.0, 90.0], [180.0, 45.0]]))
    assert s1.shape == (2, 2)
    assert s1[0, 0] == s2[0, 0]
    q = mie.efficiencies(x, m)
    assert abs(4 * s1[0, 0].real / x**2 - q.qext) <= 1e-12 * q.qext  # B&H 4.76
    assert abs(4 * abs(s1[1, 0]) ** 2 / x**2 - q.qback) <= 1e-12 * q.qback  # B&H 4.82
    a, b = mie.coefficients(x, m)
    assert len(a) == len(b) == q.terms


def test_phase_function_and_moments():
    x, m = 50.0, 1.33 + 1e-8j
    chi = mie.legendre_moments(x, m)
    q = mie.efficiencies(x, m)
    # legendre_moments.hpp's worked example: chi[1] = g, chi[2] = 0.769771, 2N+1 entries.
    assert chi[0] == pytest.approx(1.0, abs=1e-14)
    assert chi[1] == pytest.approx(q.g, abs=1e-13)
    assert round(chi[2], 6) == 0.769771
    assert len(chi) == 2 * q.terms + 1
    assert len(mie.legendre_moments(x, m, 10)) == 11
    e = mie.scattering_matrix_expansion(x, m, 10)
    np.testing.assert_allclose(e.alpha1, (2 * np.arange(11) + 1) * chi[:11], rtol=1e-12, atol=1e-13)
    assert round(e.beta1[2], 6) == -0.017994
    angles = np.linspace(0, 180, 37)
    p = mie.phase_function(x, m, angles)
    np.testing.assert_allclose(mie.phase_function_from_moments(chi, angles), p, rtol=1e-9)
    # Normalisation: 1/2 int p dmu = 1 (Gauss-Legendre in mu).
    mu, w = np.polynomial.legendre.leggauss(400)
    p_mu = mie.phase_function(x, m, np.degrees(np.arccos(mu)))
    assert 0.5 * np.sum(w * p_mu) == pytest.approx(1.0, abs=1e-9)
    assert np.allclose(mie.phase_function(x, m, angles, normalization="1"), p / (4 * np.pi))


def test_lidar_matches_the_library():
    x = np.array([0.5, 5.0, 50.0])
    m = 1.33 + 1e-8j
    got = mie.lidar(x, m)
    for i, xi in enumerate(x):
        ref = core.lidar(float(xi), m)
        assert (got.backscatter_per_sr[i], got.lidar_ratio_sr[i], got.linear_depolarisation[i]) == pytest.approx(
            ref, rel=1e-15)
    assert np.isnan(mie.lidar([-1.0], m, errors="nan").lidar_ratio_sr[0])


def test_docstrings():
    for f in (mie.efficiencies, mie.amplitudes, mie.scattering_matrix, mie.phase_function, mie.legendre_moments,
              mie.scattering_matrix_expansion, mie.coefficients):
        assert f.__doc__ and "degrees" in mie.__doc__
    assert "n + ik" in mie.efficiencies.__doc__


def test_ctrl_c_interrupts_a_long_call(interrupted_child):
    run = interrupted_child("""
        import numpy as np
        from attenuvis import mie
        x = np.full(200_000, 2e4)                 # ~4e9 series terms: minutes of work
        """, "mie.efficiencies(x, 1.33 + 1e-8j)", timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert float(run.stdout.split()[2]) < 1.0, run.stdout


def test_layered_one_layer_is_efficiencies_and_layers_broadcast():
    # One layer is the homogeneous sphere, bit for bit (the C++ dispatch).
    x = np.array([0.1, 1.0, 30.0])
    one = mie.layered_efficiencies(x[:, None], [1.5 + 0.01j])
    ref = mie.efficiencies(x, 1.5 + 0.01j)
    assert np.array_equal(one.qext, ref.qext) and np.array_equal(one.g, ref.g)
    # Leading axes broadcast; the layer axis lists core and shell.
    xs = np.stack([x, 2 * x], axis=-1)
    q = mie.layered_efficiencies(xs, [1.75 + 0.44j, 1.43 + 1e-8j])
    assert q.qext.shape == (3,)
    grid = mie.layered_efficiencies(xs[:, None, :], np.array([[1.75 + 0.44j, 1.43 + 1e-8j], [1.5, 1.33]])[None, :, :])
    assert grid.qext.shape == (3, 2)
    assert grid.qext[1, 0] == q.qext[1]


def test_layered_same_as_command_line(cli):
    # The same particle through the CLI's --x-layers: the same digits.
    out = subprocess.run([cli, "mie", "--x-layers", "5.71:1.75+0.44i,11.42:1.43+1e-8i", "--json"],
                         capture_output=True, text=True, check=True).stdout
    j = json.loads(out)
    q = mie.layered_efficiencies([5.71, 11.42], [1.75 + 0.44j, 1.43 + 1e-8j])
    assert j["qext"] == q.qext and j["qback"] == q.qback and j["g"] == q.g


def test_layered_bad_particles():
    with pytest.raises(ValueError, match="element 1: mie: layer 1: size parameters must not decrease"):
        mie.layered_efficiencies([[1.0, 2.0], [2.0, 1.0]], [1.5, 1.33])
    q = mie.layered_efficiencies([[1.0, 2.0], [2.0, 1.0]], [1.5, 1.33], errors="nan")
    assert np.isnan(q.qext[1]) and not np.isnan(q.qext[0])
    with pytest.raises(TypeError, match="last axis listing the layers"):
        mie.layered_efficiencies(1.0, 1.5)
    with pytest.raises(ValueError, match="do not broadcast"):
        mie.layered_efficiencies([1.0, 2.0, 3.0], [1.5, 1.33])
