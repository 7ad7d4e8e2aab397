# SPDX-License-Identifier: MIT
"""NetCDF out, read by the real clients: `runnel export --format netcdf` of a checkpoint and of a
series, and Model.to_xarray(), opened with xarray and with GDAL and georeferenced as the input
GeoTIFF (made with GDAL) is."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

gdal = pytest.importorskip("osgeo.gdal", reason="GDAL's Python bindings are not installed (python3-gdal)")
osr = pytest.importorskip("osgeo.osr")
xr = pytest.importorskip("xarray", reason="xarray is not installed (scripts/setup-python.sh)")
pytest.importorskip("netCDF4", reason="netCDF4 is not installed (scripts/setup-python.sh)")

import runnel  # noqa: E402
from conftest import RUNNEL_BINARY  # noqa: E402

TRANSFORM = (700000.0, 83.0, 0.0, 4000000.0, 0.0, -83.0)


def write_utm_dem(path, heights, nodata=None):
    """A 24 x 20 GeoTIFF on TRANSFORM in UTM zone 16N (made with GDAL), NODATA where given."""
    ds = gdal.GetDriverByName("GTiff").Create(str(path), 24, 20, 1, gdal.GDT_Float32)
    ds.SetGeoTransform(TRANSFORM)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32616)
    ds.SetProjection(srs.ExportToWkt())
    band = ds.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    band.WriteArray(heights)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("nc")
    dem = folder / "dem.tif"
    j, i = np.mgrid[0:20, 0:24]
    write_utm_dem(dem, (300 + 2.0 * i + 5.0 * j + 3 * np.sin(i)).astype(np.float32))
    out = folder / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--terrain", str(dem), "--model", "pipe", "--set", "run.steps=5",
                        "--series-every", "2", "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for source, target in (("final.h5", "final.nc"), ("series.h5", "series.nc")):
        r = subprocess.run([RUNNEL_BINARY, "export", str(out / source), "--format", "netcdf", "-o",
                            str(folder / target)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    return folder


def pixel_centres():
    x = TRANSFORM[0] + (np.arange(24) + 0.5) * TRANSFORM[1]
    y = TRANSFORM[3] + (np.arange(20) + 0.5) * TRANSFORM[5]
    return x, y


def test_xarray_reads_the_checkpoint_at_the_pixel_centres(run):
    with xr.open_dataset(run / "final.nc") as d:
        x, y = pixel_centres()
        assert np.array_equal(d.x.values, x) and np.array_equal(d.y.values, y)
        assert d.height.dims == ("time", "y", "x") and d.height.attrs["units"] == "m"
        assert d.height.attrs["grid_mapping"] == "spatial_ref"
        assert "UTM zone 16N" in d.spatial_ref.attrs["crs_wkt"]
        assert d.attrs["Conventions"] == "CF-1.8"
        final = runnel.read_terrain(str(run / "run" / "final.tif"))
        assert np.array_equal(d.height.values[0], final.heights)
        assert "water_depth" in d and float(d.water_depth.max()) > 0


def test_gdal_reads_the_input_geotiffs_georeferencing_back(run):
    nc = gdal.Open(f'NETCDF:"{run / "final.nc"}":height')
    tif = gdal.Open(str(run / "dem.tif"))
    assert nc.GetGeoTransform() == pytest.approx(tif.GetGeoTransform(), abs=1e-6)
    a, b = osr.SpatialReference(), osr.SpatialReference()
    a.ImportFromWkt(nc.GetProjection())
    b.ImportFromWkt(tif.GetProjection())
    assert a.IsSame(b)


def test_a_series_is_one_netcdf_with_a_time_axis(run):
    with xr.open_dataset(run / "series.nc") as d:
        # A CF time coordinate on the nominal epoch: xarray decodes it; the seconds are its offsets.
        seconds = (d.time.values - np.datetime64("1970-01-01T00:00:00")) / np.timedelta64(1, "s")
        assert seconds.tolist() == pytest.approx([0.0, 0.1, 0.2, 0.25])
        assert d.time.encoding["units"] == "seconds since 1970-01-01 00:00:00"
        assert d.time.attrs["standard_name"] == "time"
        assert d.height.shape == (4, 20, 24)
        with xr.open_dataset(run / "final.nc") as final:
            assert np.array_equal(d.height.values[-1], final.height.values[0]), "the last frame is the end"
        assert float(np.abs(d.dh.values[0]).max()) == 0.0, "no change at t = 0"


def test_to_xarray_matches_the_netcdf_export(run, tmp_path):
    model = runnel.Model.load_checkpoint(str(run / "run" / "final.h5"))
    d = model.to_xarray()
    with xr.open_dataset(run / "final.nc") as exported:
        assert np.array_equal(d.x.values, exported.x.values) and np.array_equal(d.y.values, exported.y.values)
        assert np.allclose(d.height.values, exported.height.values, rtol=0, atol=1e-4)  # float32 at 400 m
        # The export's Δh is exact; Python's takes the initial heights' float32 view (3e-5 m at 400 m).
        assert np.allclose(d.dh.values, exported.dh.values, rtol=0, atol=3e-5)
        assert d.spatial_ref.attrs == exported.spatial_ref.attrs
        assert d.time.values.tolist() == exported.time.values.tolist()
        assert d.time.attrs == exported.time.attrs
    d.to_netcdf(tmp_path / "from_python.nc")
    assert gdal.Open(f'NETCDF:"{tmp_path / "from_python.nc"}":height').GetGeoTransform() == \
        pytest.approx(TRANSFORM, abs=1e-6)


def test_a_netcdf_export_is_named_nc(run, tmp_path):
    r = subprocess.run([RUNNEL_BINARY, "export", str(run / "run" / "final.h5"), "--format", "netcdf", "-o",
                        str(tmp_path / "final.h5.out")], capture_output=True, text=True)
    assert r.returncode == 2 and ".nc" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "final.h5.out").exists()


def test_the_exports_are_cf_valid_by_the_cf_checker(run, tmp_path):
    """cfchecks (PyPI cfchecker, CF-1.8) on the checkpoint's and the series' export, georeferenced, and on a
    landscape model's and an iteration model's checkpoint without a CRS: 0 errors and 0 warnings. The CF tables
    it needs are bundled (tests/data/cf: the standard names runnel uses, empty area and region tables), so the
    check needs no network."""
    cfchecks = shutil.which("cfchecks", path=os.path.dirname(sys.executable)) or shutil.which("cfchecks")
    if cfchecks is None:
        pytest.skip("cfchecker is not installed (scripts/setup-python.sh)")
    tables = Path(__file__).parent / "data" / "cf"
    files = [run / "final.nc", run / "series.nc"]
    for model in ("stream-power", "droplet"):
        out = tmp_path / model
        r = subprocess.run([RUNNEL_BINARY, "run", "--generate", "fbm", "--set", "terrain.size=17", "--model", model,
                            "--steps", "2", "--quiet", "--out", str(out)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        r = subprocess.run([RUNNEL_BINARY, "export", str(out / "final.h5"), "--format", "netcdf", "-o",
                            str(out / "final.nc")], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        files.append(out / "final.nc")
    for nc in files:
        r = subprocess.run([cfchecks, "-v", "1.8", "-s", str(tables / "cf-standard-name-table.xml"),
                            "-a", str(tables / "area-type-table.xml"), "-r", str(tables / "standardized-region-list.xml"),
                            str(nc)], capture_output=True, text=True, timeout=300)
        report = r.stdout + r.stderr
        assert "ERRORS detected: 0" in report and "WARNINGS given: 0" in report, f"{nc}:\n{report[-3000:]}"


def test_a_georeferenced_export_names_its_grid_mapping(run):
    with xr.open_dataset(run / "final.nc") as d:
        assert d.spatial_ref.attrs["grid_mapping_name"] == "transverse_mercator"
        assert d.spatial_ref.attrs["longitude_of_central_meridian"] == pytest.approx(-87.0)  # UTM zone 16
        assert d.spatial_ref.attrs["scale_factor_at_central_meridian"] == pytest.approx(0.9996)


def test_nodata_holes_stay_holes_in_the_series_export_and_to_xarray(tmp_path):
    # A GeoTIFF with NODATA at (row 5, column 7): filled to run, then NaN (the _FillValue decoded) at that
    # pixel, and only there, in every frame of the series' NetCDF and in Model.to_xarray().
    dem = tmp_path / "holed.tif"
    j, i = np.mgrid[0:20, 0:24]
    heights = (300 + 2.0 * i + 5.0 * j).astype(np.float32)
    heights[5, 7] = -9999
    write_utm_dem(dem, heights, nodata=-9999)
    out = tmp_path / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--terrain", str(dem), "--model", "pipe", "--set", "run.steps=4",
                        "--series-every", "2", "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([RUNNEL_BINARY, "export", str(out / "series.h5"), "--format", "netcdf", "-o",
                        str(tmp_path / "series.nc")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    hole = np.zeros((20, 24), bool)
    hole[5, 7] = True
    with xr.open_dataset(tmp_path / "series.nc") as d:
        for name in ("height", "dh", "water_depth"):
            values = d[name].values
            assert np.isnan(values[:, hole]).all(), name
            assert not np.isnan(values[:, ~hole]).any(), name
    d = runnel.Model.load_checkpoint(str(out / "final.h5")).to_xarray()
    for name in ("height", "dh", "water_depth"):
        assert np.array_equal(np.isnan(d[name].values[0]), hole), name
