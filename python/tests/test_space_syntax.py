"""The space-syntax measures against networkx (space_syntax_reference.py):
random graphs (connected or not, with isolated nodes, stacked nodes on a
grid), every measure, every radius, contrast thresholds 0, 0.02 and 0.5,
and small scenes through the visibility pass, whose own edge list is handed
to networkx.  Counts and depths must be equal; sums of doubles agree to
1e-12 relative (the C++ sums in its own node order).
"""

import numpy as np
import pytest

from attenuvis import visgraph as vg

import space_syntax_reference as ref

EVERY = ("connectivity,clustering,clustering-weighted,control,controllability,mean-depth,integration,entropy,"
         "metric,component,through-vision,step-depth")
EXACT = {"connectivity", "node_count", "component_size", "through_vision", "step_depth"}


def grid_graph(seed, n_cells=12, spacing=1.5, p=0.2, stacked=3, isolated=3):
    """Nodes on random cells of a square grid (some cells holding two nodes at different heights) and a
    random graph over them; a few nodes left without edges."""
    rng = np.random.default_rng(seed)
    cells = rng.choice(n_cells * n_cells, size=40, replace=False)
    xy = np.column_stack([cells % n_cells, cells // n_cells]) * spacing + np.array([100.25, -7.5])
    eyes = np.column_stack([xy, rng.uniform(0, 3, len(xy))])
    extra = eyes[:stacked].copy()
    extra[:, 2] += 4.0
    eyes = np.vstack([eyes, extra])
    n = len(eyes)
    pairs = [(a, b) for a in range(n - isolated) for b in range(a + 1, n - isolated) if rng.random() < p]
    i = np.array([a for a, _ in pairs], dtype=np.uint32)
    j = np.array([b for _, b in pairs], dtype=np.uint32)
    return eyes, i, j


def expected(eyes, i, j, sigma, eps, radius, spacing=None, origins=()):
    n = len(eyes)
    d = ref.distances(eyes, i, j)
    g = ref.weather_graph(n, i, j, d, sigma, eps)
    full = ref.weather_graph(n, i, j, d, sigma, 0.0)
    out = ref.local_measures(g, sigma)
    suffix = f"_r{radius}" if radius else ""
    for name, values in ref.global_measures(g, radius).items():
        out[name + suffix] = values
    out.update(ref.metric_measures(g, full, sigma))
    out["component_size"] = ref.component_sizes(g)
    if spacing:
        out.update(ref.through_vision(g, eyes, spacing))
    if origins:
        out["step_depth"] = ref.step_depths(g, origins)
    return out


def compare(result, k, reference, measures=None):
    names = measures if measures is not None else reference.keys()
    assert set(names) <= set(result.measures), sorted(set(names) - set(result.measures))
    for name in names:
        got, want = result.measures[name][k], reference[name]
        if name.split("_r")[0] in EXACT:
            np.testing.assert_array_equal(got, want, err_msg=name)
        elif name == "through_vision_weighted":
            # Fixed point: each line's C rounded to 2^-33 (space_syntax.hpp).
            bound = result.measures["through_vision"][k] * 2.0 ** -33 + 1e-15
            assert np.all(np.abs(got - want) <= bound), name
        else:
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12, err_msg=name)


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("radius", [0, 1, 2, 3])
def test_random_graphs_every_measure(seed, radius):
    eyes, i, j = grid_graph(seed)
    sigmas = [0.0, 0.05, 0.4]
    for eps in (0.0, 0.02, 0.5):
        r = vg.space_syntax_of_graph(eyes, i, j, sigmas, measures=EVERY, radius=radius, threshold=eps,
                                     spacing=1.5, origins=[0, 5])
        for k, sigma in enumerate(sigmas):
            want = expected(eyes, i, j, sigma, eps, radius, spacing=1.5, origins=(0, 5))
            compare(r, k, want)
            assert r.lines[k] == int(want["connectivity"].sum()) // 2
            assert r.components[k] == round(float(np.sum(1.0 / want["component_size"])))


def test_disconnected_and_isolated_nodes():
    # Two triangles and a lone node: components 3, 3, 1; the lone node gets -1 where depthmapX writes -1.
    eyes = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [10, 0, 0], [11, 0, 0], [10, 1, 0], [20, 20, 0]], float)
    i = np.array([0, 0, 1, 3, 3, 4], dtype=np.uint32)
    j = np.array([1, 2, 2, 4, 5, 5], dtype=np.uint32)
    r = vg.space_syntax_of_graph(eyes, i, j, [0.1], measures=EVERY.replace(",through-vision,step-depth", ""))
    assert r.components == [3]
    np.testing.assert_array_equal(r["component_size"][0], [3, 3, 3, 3, 3, 3, 1])
    np.testing.assert_array_equal(r["clustering"][0][-1], -1)
    np.testing.assert_array_equal(r["mean_depth"][0][-1], -1)
    compare(r, 0, expected(eyes, i, j, 0.1, 0.02, 0))


def test_threshold_splits_the_graph():
    # A chain 0-1-2-3 with one long link: fog (sigma 0.5, eps 0.02: range ln 50 / 0.5 = 7.8 m) cuts it.
    eyes = np.array([[0, 0, 0], [5, 0, 0], [15, 0, 0], [20, 0, 0]], float)
    i = np.array([0, 1, 2], dtype=np.uint32)
    j = np.array([1, 2, 3], dtype=np.uint32)
    r = vg.space_syntax_of_graph(eyes, i, j, [0.0, 0.5], measures="component,mean-depth")
    assert r.lines == [3, 2]
    assert r.components == [1, 2]
    np.testing.assert_array_equal(r["component_size"], [[4, 4, 4, 4], [2, 2, 2, 2]])
    # Clear: depths from node 0 are 1, 2, 3 (TD 6, n 4, MD 2); fog: 1 (MD 1).
    np.testing.assert_array_equal(r["mean_depth"][:, 0], [2.0, 1.0])


def test_same_graph_is_reported():
    eyes, i, j = grid_graph(3)
    r = vg.space_syntax_of_graph(eyes, i, j, [0.0, 1e-4, 0.05], measures="integration", threshold=0.02)
    # 1e-4/m keeps every line of this 20 m graph: the same graph as clear.
    assert r.same_graph_as[:2] == [-1, 0]
    np.testing.assert_array_equal(r["integration_hh"][0], r["integration_hh"][1])


@pytest.mark.parametrize("layout", range(5))
def test_layouts_at_5m_through_the_pass(layout):
    # The pass's own edge list (edges=True) to networkx, every measure, clear and a fog at eps 0.5.
    scene = vg.Scene.layout(layout)
    eyes = vg.node_grid(scene, 5.0)
    sigmas = [1.5e-4, 0.0287]
    edges = vg.all_to_all(scene, eyes, sigmas, edges=True).edges
    for radius in (0, 2):
        r = vg.space_syntax(scene, eyes, sigmas, measures=EVERY, radius=radius, threshold=0.5, spacing=5.0,
                            origins=[0])
        assert r.stats["pairs_visible"] == len(edges.i)
        for k, sigma in enumerate(sigmas):
            compare(r, k, expected(eyes, edges.i, edges.j, sigma, 0.5, radius, spacing=5.0, origins=(0,)))


def test_bad_input_raises():
    eyes, i, j = grid_graph(1)
    with pytest.raises(ValueError, match="unknown measure 'integraton'"):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], measures="integraton")
    with pytest.raises(ValueError, match="through-vision needs spacing="):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], measures="all")
    with pytest.raises(ValueError, match="step depth needs"):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], measures="step-depth")
    with pytest.raises(ValueError, match="contrast threshold"):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], threshold=1.0)
    with pytest.raises(ValueError, match="given twice"):
        vg.space_syntax_of_graph(eyes, np.r_[i, i[:1]], np.r_[j, j[:1]], [0.0], measures="connectivity")
    with pytest.raises(ValueError, match="radius"):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], radius="m")
    with pytest.raises(ValueError, match="not on a square grid"):
        vg.space_syntax_of_graph(eyes, i, j, [0.0], measures="through-vision", spacing=1.0)


def test_threads_do_not_change_the_result():
    scene = vg.Scene.layout(3)
    eyes = vg.node_grid(scene, 2.5)
    a = vg.space_syntax(scene, eyes, [1.5e-4, 0.03], measures="all", threshold=0.5, spacing=2.5, threads=1)
    b = vg.space_syntax(scene, eyes, [1.5e-4, 0.03], measures="all", threshold=0.5, spacing=2.5, threads=3)
    for name in a.measures:
        assert a[name].tobytes() == b[name].tobytes(), name


def test_bit_rows_and_csr_agree():
    eyes, i, j = grid_graph(5)
    kw = dict(measures=EVERY, radius=2, threshold=0.02, spacing=1.5, origins=[1])
    a = vg.space_syntax_of_graph(eyes, i, j, [0.0, 0.2], graph="bit-rows", **kw)
    b = vg.space_syntax_of_graph(eyes, i, j, [0.0, 0.2], graph="csr", **kw)
    for name in a.measures:
        assert a[name].tobytes() == b[name].tobytes(), name
