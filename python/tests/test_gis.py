# SPDX-License-Identifier: MIT
"""Every 3-D export and the couplers' grids put a vertex where GDAL puts its raster value: at the
pixel's centre. A georeferenced GeoTIFF made with GDAL goes through runnel run; the series grid, the
OBJ mesh, the BMI origin and the Landlab grid are compared with GDAL's pixel centres, to the metre
and far below it."""
import subprocess

import numpy as np
import pytest

gdal = pytest.importorskip("osgeo.gdal", reason="GDAL's Python bindings are not installed (python3-gdal)")
h5py = pytest.importorskip("h5py", reason="h5py is not installed (python3-h5py)")
osr = pytest.importorskip("osgeo.osr")

import runnel  # noqa: E402
from conftest import RUNNEL_BINARY  # noqa: E402

NX, NY, CELL = 24, 20, 83.0
TRANSFORM = (700000.0, CELL, 0.0, 4000000.0, 0.0, -CELL)


@pytest.fixture(scope="module")
def dem(tmp_path_factory):
    folder = tmp_path_factory.mktemp("gis")
    path = folder / "dem.tif"
    ds = gdal.GetDriverByName("GTiff").Create(str(path), NX, NY, 1, gdal.GDT_Float32)
    ds.SetGeoTransform(TRANSFORM)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32616)
    ds.SetProjection(srs.ExportToWkt())
    j, i = np.mgrid[0:NY, 0:NX]
    ds.GetRasterBand(1).WriteArray((300 + 2.0 * i + 5.0 * j + 3 * np.sin(i)).astype(np.float32))
    ds = None
    return path


def gdal_pixel_centres(path):
    """GDAL's own map coordinates of every pixel's centre: (x, y), (NY, NX), row 0 the northern."""
    ds = gdal.Open(str(path))
    gt = ds.GetGeoTransform()
    x = np.empty((ds.RasterYSize, ds.RasterXSize))
    y = np.empty_like(x)
    for row in range(ds.RasterYSize):
        for column in range(ds.RasterXSize):
            x[row, column], y[row, column] = gdal.ApplyGeoTransform(gt, column + 0.5, row + 0.5)
    return x, y


@pytest.fixture(scope="module")
def pipe_run(dem):
    out = dem.parent / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--terrain", str(dem), "--model", "pipe", "--set", "run.steps=4",
                        "--series-every", "2", "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def test_the_series_grid_is_at_gdals_pixel_centres(dem, pipe_run):
    x, y = gdal_pixel_centres(dem)
    with h5py.File(pipe_run / "series.h5", "r") as f:
        assert np.abs(f["grid/x"][()] - x).max() < 1e-6
        assert np.abs(f["grid/y"][()] - y).max() < 1e-6


def test_the_obj_mesh_is_at_gdals_pixel_centres(dem, pipe_run, tmp_path):
    r = subprocess.run([RUNNEL_BINARY, "export", str(pipe_run / "final.h5"), "--format", "obj", "-o",
                        str(tmp_path / "t.obj")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    vertices = np.array([line.split()[1:4] for line in (tmp_path / "t.obj").read_text().splitlines()
                         if line.startswith("v ")], dtype=float)
    x, y = gdal_pixel_centres(dem)
    assert np.abs(vertices[:, 0] - x.reshape(-1)).max() < 1e-6
    assert np.abs(vertices[:, 1] - y.reshape(-1)).max() < 1e-6
    heights = gdal.Open(str(dem)).ReadAsArray()
    assert np.abs(vertices[:, 2] - heights.reshape(-1)).max() < 0.01, "z up: the heights (eroded a little)"


def test_bmi_and_landlab_put_node_zero_at_the_south_west_pixel_centre(dem, tmp_path):
    pytest.importorskip("bmipy", reason="bmipy is not installed (scripts/setup-python.sh)")
    from runnel.bmi import RunnelBmi

    x, y = gdal_pixel_centres(dem)
    scenario = tmp_path / "s.toml"
    scenario.write_text(f'[run]\nmodel = "thermal"\niterations = 2\n[terrain]\nfile = "{dem}"\n')
    bmi = RunnelBmi()
    bmi.initialize(str(scenario))
    origin = bmi.get_grid_origin(0, np.empty(2))
    assert abs(origin[0] - y[-1, 0]) < 1e-6 and abs(origin[1] - x[-1, 0]) < 1e-6
    bmi.finalize()
    pytest.importorskip("landlab", reason="Landlab is not installed (scripts/setup-python.sh)")
    grid = runnel.read_terrain(str(dem)).to_landlab()
    assert np.abs(grid.x_of_node.reshape(NY, NX) - np.flipud(x)).max() < 1e-6
    assert np.abs(grid.y_of_node.reshape(NY, NX) - np.flipud(y)).max() < 1e-6
