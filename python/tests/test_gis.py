"""City models from GIS data and results back to a GIS: a DEM and a layer of
footprints written here with GDAL (python3-gdal), run end to end from the
command line (the GeoPackage read back with GDAL and compared, value by
value and CRS, with the CSV) and from Python (Scene.from_footprints,
Scene.from_file(terrain=...)); result.to_geopandas with and without
geopandas."""

import csv
import json
import math
import subprocess
import sys
import types

import numpy as np
import pytest

from attenuvis import visgraph as vg

gdal = pytest.importorskip("osgeo.gdal")
ogr = pytest.importorskip("osgeo.ogr")
osr = pytest.importorskip("osgeo.osr")
gdal.UseExceptions()

EPSG = 32632
X0, Y_TOP = 500000.0, 5000100.0  # the DEM's top-left corner


def plane(x, y):
    """The DEM's surface: a plane, so that the nodes' heights are known exactly."""
    return 300.0 + 0.1 * (x - X0) + 0.05 * (y - (Y_TOP - 100))


def write_dem(path, cols=120, rows=100, nodata=()):
    ds = gdal.GetDriverByName("GTiff").Create(str(path), cols, rows, 1, gdal.GDT_Float32)
    ds.SetGeoTransform([X0, 1.0, 0.0, Y_TOP, 0.0, -1.0])
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(EPSG)
    ds.SetProjection(srs.ExportToWkt())
    x = X0 + 0.5 + np.arange(cols)
    y = Y_TOP - 0.5 - np.arange(rows)
    z = plane(x[None, :], y[:, None]).astype(np.float32)
    for c, r in nodata:
        z[r, c] = -9999
    band = ds.GetRasterBand(1)
    band.SetNoDataValue(-9999)
    band.WriteArray(z)
    ds = None


def square(x0, y0, x1, y1):
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]:
        ring.AddPoint_2D(X0 + x, Y_TOP - 100 + y)
    return ring


def write_footprints(path, epsg=EPSG):
    """Three buildings with heights (one around a courtyard) and one without."""
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    layer = ds.CreateLayer("buildings", srs, ogr.wkbPolygon)
    layer.CreateField(ogr.FieldDefn("height", ogr.OFTReal))
    for rings, height in [([square(20, 20, 30, 30)], 12.0), ([square(50, 20, 80, 50), square(60, 30, 70, 40)], 9.0),
                          ([square(20, 60, 28, 68)], 15.0), ([square(90, 70, 95, 75)], None)]:
        polygon = ogr.Geometry(ogr.wkbPolygon)
        for ring in rings:
            polygon.AddGeometry(ring)
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(polygon)
        if height is not None:
            feature.SetField("height", height)
        layer.CreateFeature(feature)
    ds = None


@pytest.fixture
def city(tmp_path):
    write_dem(tmp_path / "dem.tif")
    write_footprints(tmp_path / "fp.gpkg")
    return tmp_path


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def test_geopackage_holds_the_csv_values_and_the_crs(cli, city):
    out, gpkg, summary = city / "n.csv", city / "n.gpkg", city / "s.json"
    subprocess.run([cli, "vg", str(city / "fp.gpkg"), "--height-field", "height", "--terrain", str(city / "dem.tif"),
                    "--conditions", "clear,fog:advection", "--spacing", "3", "--distances", "--out", str(out),
                    "--gpkg", str(gpkg), "--summary", str(summary), "--quiet"], check=True)
    rows = read_csv(out)
    ds = ogr.Open(str(gpkg))
    assert ds.GetLayerCount() == 1
    layer = ds.GetLayer(0)
    assert layer.GetName() == "nodes"
    assert layer.GetFeatureCount() == len(rows) > 100
    # The CRS: the footprints', which the summary names too.
    assert layer.GetSpatialRef().GetAuthorityName(None) == "EPSG"
    assert layer.GetSpatialRef().GetAuthorityCode(None) == str(EPSG)
    assert json.loads(summary.read_text())["scene"]["crs"] == f"EPSG:{EPSG}"
    definition = layer.GetLayerDefn()
    fields = [definition.GetFieldDefn(i).GetName() for i in range(definition.GetFieldCount())]
    columns = list(rows[0].keys())
    assert fields == ["node"] + columns[3:]
    assert "avg:fog:advection" in fields and "max_distance" in fields
    nulls = 0
    for feature in layer:
        i = feature.GetField("node")
        row = rows[i]
        point = feature.GetGeometryRef()
        # Every value exactly (the CSV prints 17 significant digits: doubles round-trip).
        assert (point.GetX(), point.GetY(), point.GetZ()) == tuple(float(row[c]) for c in "xyz")
        for name in columns[3:]:
            if row[name] == "nan":
                assert feature.IsFieldNull(name)
                nulls += 1
            else:
                assert feature.GetField(name) == float(row[name]), (i, name)
    # Nodes on the DEM's surface, 1.7 m up.
    for row in rows:
        assert float(row["z"]) - 1.7 == pytest.approx(plane(float(row["x"]), float(row["y"])), abs=1e-3)


def test_outputs_appear_all_or_none(cli, city):
    # A GeoPackage that cannot be written (no such directory): the run fails
    # and leaves no CSV either.
    run = subprocess.run([cli, "vg", str(city / "fp.gpkg"), "--height-field", "height", "--terrain",
                          str(city / "dem.tif"), "--conditions", "clear", "--spacing", "4", "--out", str(city / "n.csv"),
                          "--gpkg", str(city / "missing" / "n.gpkg")], capture_output=True, text=True)
    assert run.returncode != 0
    assert "attenuvis: error:" in run.stderr and "n.gpkg" in run.stderr
    assert sorted(p.name for p in city.iterdir()) == ["dem.tif", "fp.gpkg"]


def test_from_footprints_on_a_dem(city):
    scene = vg.Scene.from_footprints(city / "fp.gpkg", height_field="height", terrain=city / "dem.tif")
    assert scene.crs == f"EPSG:{EPSG}"
    assert scene.ground.startswith("a DEM, ") and "EPSG:32632" in scene.ground
    assert any("1 of 4 features have no usable height" in w for w in scene.warnings)
    eyes = vg.node_grid(scene, 2.0)
    np.testing.assert_allclose(eyes[:, 2] - 1.7, plane(eyes[:, 0], eyes[:, 1]), atol=1e-3)
    # The courtyard (x 60..70, y 30..40 above the DEM's lower edge) holds
    # 5 x 5 nodes; the buildings none.
    x, y = eyes[:, 0] - X0, eyes[:, 1] - (Y_TOP - 100)
    assert np.count_nonzero((x > 60) & (x < 70) & (y > 30) & (y < 40)) == 25
    assert not np.any((x > 20) & (x < 30) & (y > 20) & (y < 30))
    r = vg.all_to_all(scene, eyes, [0.0])
    assert r.stats["pairs_visible"] > 0
    with pytest.raises(ValueError, match="feature 4 has no usable height"):
        vg.Scene.from_footprints(city / "fp.gpkg", height_field="height", strict=True)
    with pytest.raises(ValueError, match="give height_field, levels_field or both"):
        vg.Scene.from_footprints(city / "fp.gpkg")


def test_from_footprints_refusals(city):
    write_footprints(city / "wgs84.gpkg", epsg=4326)
    with pytest.raises(ValueError, match=r"degrees: a projected CRS in metres is needed"):
        vg.Scene.from_footprints(city / "wgs84.gpkg", height_field="height")
    write_dem(city / "hole.tif", nodata=[(45, 50)])
    with pytest.raises(ValueError, match=r"no data at cell \(column 45, row 50\)"):
        vg.Scene.from_footprints(city / "fp.gpkg", height_field="height", terrain=city / "hole.tif")
    write_dem(city / "short.tif", cols=40)
    with pytest.raises(ValueError, match="does not cover the model"):
        vg.Scene.from_footprints(city / "fp.gpkg", height_field="height", terrain=city / "short.tif")
    with pytest.raises(ValueError, match="not a scene"):
        vg.Scene.from_file(city / "fp.gpkg")


def write_hillside_obj(path):
    """Four 10 m boxes on a 20 % slope (z = 0.2 x), their feet on it, no ground."""
    lines, n = [], 0
    for bx, by in [(0, 0), (30, 0), (0, 30), (30, 30)]:
        lines.append(f"g house-{bx}-{by}")
        corners = [(bx, by), (bx + 10, by), (bx + 10, by + 10), (bx, by + 10)]
        roof = 0.2 * (bx + 10) + 8
        for x, y in corners:
            lines.append(f"v {x} {y} {0.2 * x}")
        for x, y in corners:
            lines.append(f"v {x} {y} {roof}")
        b = n + 1
        lines += [f"f {b} {b + 2} {b + 1}", f"f {b} {b + 3} {b + 2}", f"f {b + 4} {b + 5} {b + 6}", f"f {b + 4} {b + 6} {b + 7}"]
        for k in range(4):
            a, c = b + k, b + (k + 1) % 4
            lines += [f"f {a} {c} {c + 4}", f"f {a} {c + 4} {a + 4}"]
        n += 8
    path.write_text("\n".join(lines) + "\n")


def test_from_file_infers_the_ground_of_a_buildings_only_model(tmp_path):
    write_hillside_obj(tmp_path / "hill.obj")
    assert len(vg.node_grid(vg.Scene.from_file(tmp_path / "hill.obj"), 2.0)) == 0  # nothing to stand on
    scene = vg.Scene.from_file(tmp_path / "hill.obj", terrain="infer")
    assert scene.ground.startswith("a TIN inferred from 4 building bases")
    eyes = vg.node_grid(scene, 2.0)
    assert len(eyes) > 100
    # The bases lie on z = 0.2 x, and so does the TIN through them.
    np.testing.assert_allclose(eyes[:, 2] - 1.7, 0.2 * eyes[:, 0], atol=1e-4)


def small_result():
    scene = vg.Scene.layout(2)
    eyes = vg.node_grid(scene, 10.0)
    return eyes, vg.all_to_all(scene, eyes, [0.0, 0.01], distance_stats=True)


def test_to_geopandas_without_geopandas(monkeypatch):
    eyes, r = small_result()
    monkeypatch.setitem(sys.modules, "geopandas", None)  # import geopandas raises ImportError
    with pytest.raises(ImportError, match="python3-geopandas"):
        r.to_geopandas(eyes, "EPSG:28992")
    columns = r.columns(["clear", "fog"])
    assert list(columns) == ["node", "degree", "sum:clear", "avg:clear", "sum:fog", "avg:fog", "mean_distance",
                             "max_distance"]
    np.testing.assert_array_equal(columns["sum:fog"], r.sum[1])


def test_to_geopandas_hands_geopandas_the_columns_points_and_crs(monkeypatch):
    # A stand-in for geopandas records what it is given (the real one, when
    # installed, is tested below).
    calls = {}
    fake = types.ModuleType("geopandas")
    fake.points_from_xy = lambda x, y, z: list(zip(x, y, z))

    class GeoDataFrame:
        def __init__(self, data, geometry, crs):
            calls.update(data=data, geometry=geometry, crs=crs)

    fake.GeoDataFrame = GeoDataFrame
    monkeypatch.setitem(sys.modules, "geopandas", fake)
    eyes, r = small_result()
    r.to_geopandas(eyes, "EPSG:28992", labels=["clear", "fog"])
    assert calls["crs"] == "EPSG:28992"
    assert calls["geometry"] == [tuple(p) for p in eyes]
    np.testing.assert_array_equal(calls["data"]["avg:clear"], r.average[0])
    with pytest.raises(ValueError, match="one name per sigma"):
        r.to_geopandas(eyes, labels=["clear"])
    with pytest.raises(ValueError, match="the result has"):
        r.to_geopandas(eyes[:3])


def test_to_geopandas_with_geopandas():
    geopandas = pytest.importorskip("geopandas")
    eyes, r = small_result()
    frame = r.to_geopandas(eyes, "EPSG:28992", labels=["clear", "fog"])
    assert frame.crs.to_epsg() == 28992
    assert len(frame) == len(eyes)
    np.testing.assert_array_equal(frame["sum:fog"].to_numpy(), r.sum[1])
    assert all(math.isclose(p.z, z) for p, z in zip(frame.geometry, eyes[:, 2]))
