"""attenuvis.visgraph against the command line, and its array handling,
edges, threads, errors and Ctrl-C."""

import csv
import subprocess

import numpy as np
import pytest

from attenuvis import visgraph as vg

SIGMAS = [1e-3, 2e-2]


@pytest.fixture(scope="module")
def layout2():
    return vg.Scene.layout(2)


def test_same_as_command_line(cli, tmp_path, layout2):
    out = tmp_path / "scores.csv"
    subprocess.run([cli, "vg", "layout:2", "--spacing", "2", "--conditions", "sigma:0.001/m,sigma:0.02/m",
                    "--out", str(out), "--quiet"], check=True)
    with open(out) as f:
        rows = list(csv.DictReader(f))
    eyes = vg.node_grid(layout2, 2.0)
    r = vg.all_to_all(layout2, eyes, SIGMAS)
    assert len(rows) == len(eyes)
    np.testing.assert_allclose([[float(row[c]) for c in "xyz"] for row in rows], eyes, rtol=1e-6)
    np.testing.assert_array_equal([int(row["degree"]) for row in rows], r.degree)
    # The CSV prints 6 significant digits.
    np.testing.assert_allclose([float(row["sum:sigma:0.001/m"]) for row in rows], r.sum[0], rtol=1e-5)
    np.testing.assert_allclose([float(row["avg:sigma:0.02/m"]) for row in rows], r.average[1], rtol=1e-5)


def test_result_shapes_and_edges(layout2):
    eyes = vg.node_grid(layout2, 4.0)
    n = len(eyes)
    r = vg.all_to_all(layout2, eyes, SIGMAS)
    assert r.sum.shape == (2, n) and r.average.shape == (2, n) and r.degree.shape == (n,)
    assert r.edges is None  # not kept unless asked
    with_edges = vg.all_to_all(layout2, eyes, SIGMAS, edges=True, distance_stats=True)
    np.testing.assert_array_equal(with_edges.sum, r.sum)  # asking for edges never changes scores
    i, j, d = with_edges.edges
    assert len(i) == r.stats["pairs_visible"] == r.degree.sum() // 2
    np.testing.assert_array_equal(np.bincount(np.concatenate([i, j]), minlength=n), r.degree)
    np.testing.assert_allclose(d, np.linalg.norm(eyes[i] - eyes[j], axis=1), rtol=1e-12)
    # S_S from the edge list: sum of exp(-sigma d) over each node's partners (fixed-point sums: <= 2^-41 per partner).
    ss = np.bincount(np.concatenate([i, j]), weights=np.exp(-SIGMAS[1] * np.concatenate([d, d])), minlength=n)
    np.testing.assert_allclose(ss, r.sum[1], rtol=0, atol=1e-12 * max(1, r.degree.max()))
    longest = np.zeros(n)
    np.maximum.at(longest, np.concatenate([i, j]), np.concatenate([d, d]))
    seen = r.degree > 0
    # Distances are summed in fixed point (2^-20 m), the maximum kept exactly.
    np.testing.assert_allclose(with_edges.max_distance[seen], longest[seen], rtol=1e-12)


def test_thread_count_independence(layout2):
    eyes = vg.node_grid(layout2, 2.0)
    a = vg.all_to_all(layout2, eyes, SIGMAS, threads=1)
    b = vg.all_to_all(layout2, eyes, SIGMAS, threads=2)
    np.testing.assert_array_equal(a.sum, b.sum)
    np.testing.assert_array_equal(a.degree, b.degree)


def test_to_targets_and_pruning(layout2):
    eyes = vg.node_grid(layout2, 2.0)
    target = np.array([[25.0, 25.0, 1.7]])
    r = vg.to_targets(layout2, eyes, target, SIGMAS, edges=True)
    assert r.sum.shape == (2, len(eyes)) and set(np.unique(r.degree)) <= {0, 1}
    assert len(r.edges.i) == r.degree.sum() and np.all(r.edges.j == 0)
    # sigma = 5/m: the pruning radius ln(1/eps)/sigma = 1.4 m holds under 10% of the pairs (along x),
    # so pruning is applied; degree is withheld and each node's S_S is within its certified bound.
    p = vg.all_to_all(layout2, eyes, [5.0], prune_below=1e-3)
    exact = vg.all_to_all(layout2, eyes, [5.0])
    assert p.degree is None, p.stats["pruning_note"]
    assert np.all(np.abs(p.sum[0] - exact.sum[0]) <= p.pruned * 1e-3 + 1e-9)
    # sigma = 0.05/m: a 138 m radius covers most pairs, where the exact culled pass is faster; the
    # run is exact, keeps every column, and says why.
    wide = vg.all_to_all(layout2, eyes, [0.05], prune_below=1e-3)
    exact = vg.all_to_all(layout2, eyes, [0.05])
    np.testing.assert_array_equal(wide.degree, exact.degree)
    np.testing.assert_array_equal(wide.sum, exact.sum)
    assert wide.stats["pruning_note"]
    # tolerance= is the former name of prune_below=: the same pass, with a DeprecationWarning.
    with pytest.warns(DeprecationWarning, match="prune_below"):
        old = vg.all_to_all(layout2, eyes, [5.0], tolerance=1e-3)
    np.testing.assert_array_equal(old.sum, p.sum)
    assert old.stats["prune_below"] == 1e-3
    with pytest.raises(TypeError, match="prune_below= only"):
        vg.all_to_all(layout2, eyes, [5.0], prune_below=1e-3, tolerance=1e-3)


def test_from_arrays_equals_obj(tmp_path):
    # A 20 x 20 m floor and a 2 m thick wall across it.
    v = np.array([[0, 0, 0], [20, 0, 0], [20, 20, 0], [0, 20, 0],
                  [9, -1, 0], [11, -1, 0], [11, 15, 0], [9, 15, 0],
                  [9, -1, 5], [11, -1, 5], [11, 15, 5], [9, 15, 5]], dtype=float)
    floor = [[0, 1, 2], [0, 2, 3]]
    box = [[4, 5, 9], [4, 9, 8], [5, 6, 10], [5, 10, 9], [6, 7, 11], [6, 11, 10], [7, 4, 8], [7, 8, 11],
           [8, 9, 10], [8, 10, 11]]
    t = np.array(floor + box)
    groups = ["floor"] * 2 + ["wall"] * 10
    scene = vg.Scene.from_arrays(v, t, groups)
    obj = tmp_path / "wall.obj"
    with open(obj, "w") as f:
        f.writelines(f"v {a} {b} {c}\n" for a, b, c in v)
        f.write("g floor\n" + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in floor))
        f.write("g wall\n" + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in box))
    from_file = vg.Scene.from_obj(obj)
    assert sorted(scene.groups) == sorted(from_file.groups) == ["floor", "wall"]
    e1 = vg.node_grid(scene, 1.0, walkable=["floor"])
    e2 = vg.node_grid(from_file, 1.0, walkable=["floor"])
    np.testing.assert_array_equal(e1, e2)
    assert e1.shape[1] == 3 and np.allclose(e1[:, 2], 1.7)
    r1 = vg.all_to_all(scene, e1, [0.01])
    r2 = vg.all_to_all(from_file, e2, [0.01])
    np.testing.assert_array_equal(r1.sum, r2.sum)
    assert r1.degree.min() < len(e1) - 1  # the wall hides some pairs
    # Non-contiguous float32 eyes give the same result.
    e32 = np.asfortranarray(e1.astype(np.float32))
    np.testing.assert_array_equal(vg.all_to_all(scene, e32, [0.01]).degree,
                                  vg.all_to_all(scene, e32.astype(np.float64), [0.01]).degree)


def test_errors_carry_the_command_line_message(cli, tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(RuntimeError) as info:
        vg.Scene.from_obj(missing)
    run = subprocess.run([cli, "vg", str(missing), "--conditions", "clear", "--out", str(tmp_path / "o.csv"),
                          "--quiet"],
                         capture_output=True, text=True)
    assert run.returncode != 0
    assert str(info.value) in run.stderr
    scene = vg.Scene.layout(0)
    with pytest.raises(ValueError, match="spacing"):
        vg.node_grid(scene, 0.0)
    with pytest.raises(ValueError, match=r"sigmas\[1\]"):
        vg.all_to_all(scene, np.zeros((2, 3)), [0.1, -1])
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        vg.all_to_all(scene, np.zeros((2, 2)), [0.1])
    with pytest.raises(ValueError, match="triangle 0"):
        vg.Scene.from_arrays(np.zeros((3, 3)), np.array([[0, 1, 5]]))


def test_progress_callback_and_its_exception(layout2):
    eyes = vg.node_grid(layout2, 0.5)
    calls = []
    vg.all_to_all(layout2, eyes[:3000], [0.01], progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1][0] == calls[-1][1] == 3000 * 2999 // 2

    def stop(done, total):
        raise RuntimeError("stop here")

    big = vg.node_grid(vg.Scene.layout(0), 0.2)
    with pytest.raises(RuntimeError, match="stop here"):
        vg.all_to_all(vg.Scene.layout(0), big, [0.01], progress=stop)


def test_ctrl_c_interrupts_a_long_pass(interrupted_child):
    run = interrupted_child("""
        from attenuvis import visgraph as vg
        scene = vg.Scene.layout(0)
        eyes = vg.node_grid(scene, 0.2)          # ~60000 eyes: minutes of work
        """, "vg.all_to_all(scene, eyes, [0.01])", timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    delay = float(run.stdout.split()[2])
    assert delay < 1.0, run.stdout
