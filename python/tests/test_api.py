# SPDX-License-Identifier: MIT
"""The package's API: terrains, models, fields, checkpoints, metrics, errors."""
import subprocess

import numpy as np
import pytest

import runnel


@pytest.fixture(scope="module")
def hills():
    return runnel.generate("fbm", 49, 41, 2.0, seed=4)


def test_generate_is_deterministic_and_seeded(hills):
    again = runnel.generate("fbm", 49, 41, 2.0, seed=4)
    other = runnel.generate("fbm", 49, 41, 2.0, seed=5)
    assert np.array_equal(hills.heights, again.heights)
    assert not np.array_equal(hills.heights, other.heights)
    assert hills.heights.shape == (41, 49) and hills.heights.dtype == np.float32


def test_terrain_heights_are_the_terrains_memory_not_a_copy():
    t = runnel.Terrain(np.zeros((3, 4), dtype=np.float32), cell=2.0)
    view = t.heights
    view[1, 2] = 5.0
    assert t.heights[1, 2] == 5.0
    assert t.volume() == pytest.approx(5.0 * 2.0 * 2.0)
    assert not view.flags["OWNDATA"]


def test_terrain_files_round_trip_with_georeferencing(hills, tmp_path):
    for ext in ("asc", "npy", "tif"):
        path = str(tmp_path / f"t.{ext}")
        runnel.write_terrain(path, hills)
        back = runnel.read_terrain(path, cell=2.0 if ext == "npy" else None)
        assert np.array_equal(back.heights, hills.heights), ext
        assert back.cell == 2.0
    dem = runnel.read_terrain(str(_utm_dem(tmp_path)))
    assert "UTM zone 16N" in dem.crs_wkt
    assert (dem.origin_x, dem.cell, dem.nodata) == (700000.0, 83.0, -9999.0)
    runnel.write_terrain(str(tmp_path / "copy.tif"), dem)
    assert runnel.read_terrain(str(tmp_path / "copy.tif")).crs_wkt == dem.crs_wkt


def _utm_dem(tmp_path):
    from conftest import SOURCE_DIR

    out = tmp_path / "utm.tif"
    subprocess.run(["gdal_translate", "-q", "-a_srs", "EPSG:32616", "-a_ullr", "700000", "4000000",
                    "733449", "3971448", "-a_nodata", "-9999",
                    str(SOURCE_DIR / "data/terrains/jacksboro_fault_dem.asc"), str(out)], check=True)
    return out


# Every model, and SPH with each of its two solvers.
@pytest.mark.parametrize("name", ["droplet", "pipe", "olsen", "thermal", "sph", "sph-dfsph"])
def test_every_model_steps_and_balances_exactly(name, hills):
    solver = {"sph.solver": "dfsph"} if name == "sph-dfsph" else {}
    model = runnel.Model(name.split("-")[0], hills, {"run.seed": 2, **solver})
    model.advance(3.0 if model.clock == "iterations" else 0.5)
    assert model.steps > 0
    balance = model.mass_balance()
    assert balance["residual_quanta"] == 0 and balance["residual"] == 0.0
    for field in model.field_names():
        values = model.field(field)
        assert np.all(np.isfinite(values)), field
    assert isinstance(model.diagnostics(), dict)


def test_fields_have_the_dictionarys_shapes(hills):
    pipe = runnel.Model("pipe", hills, {"pipe.rain": 0.05})
    pipe.advance(2.0)
    assert pipe.field("topographic__elevation").shape == (41, 49)
    assert pipe.field("surface_water__depth").shape == (41, 49)
    assert pipe.field("surface_water__outflux").shape == (41, 49, 4)
    assert pipe.field("sediment__suspended").dtype == np.int64
    assert pipe.field("surface_water__depth").max() > 0
    sph = runnel.Model("sph", runnel.generate("fbm", 33, 33, 1.0, seed=1))
    for _ in range(30):
        sph.step()
    positions = sph.field("particle__position")
    ids = sph.field("particle__id")
    assert positions.shape == (len(ids), 3) and len(ids) > 0
    assert len(np.unique(ids)) == len(ids)


def run_straight_and_resumed(make, steps, tmp_path):
    """A model run `steps` steps straight, and one saved halfway, loaded back and run to the same step."""
    whole, half = make(), make()
    for _ in range(steps):
        whole.step()
    for _ in range(steps // 2):
        half.step()
    half.save_checkpoint(str(tmp_path / "half.h5"))
    resumed = runnel.Model.load_checkpoint(str(tmp_path / "half.h5"))
    for _ in range(steps - steps // 2):
        resumed.step()
    return whole, resumed


def test_a_checkpoint_resumes_bit_for_bit(hills, tmp_path):
    whole, resumed = run_straight_and_resumed(lambda: runnel.Model("pipe", hills, {"pipe.rain": 0.03}),
                                              50, tmp_path)
    assert resumed.steps == whole.steps
    assert np.array_equal(resumed.terrain().heights, whole.terrain().heights)
    assert np.array_equal(resumed.field("sediment__suspended"), whole.field("sediment__suspended"))


@pytest.mark.parametrize("solver", ["wcsph", "dfsph"])
def test_an_sph_checkpoint_resumes_bit_for_bit_with_either_solver(tmp_path, solver):
    terrain = runnel.generate("fbm", 33, 33, 1.0, seed=1)
    settings = {"sph.solver": solver, "rain.rate": 2000.0}
    whole, resumed = run_straight_and_resumed(lambda: runnel.Model("sph", terrain, settings), 40, tmp_path)
    assert resumed.time == whole.time and resumed.steps == whole.steps
    assert np.array_equal(resumed.field("particle__position"), whole.field("particle__position"))
    assert len(whole.field("particle__id")) > 0, "the drops have fallen"
    assert resumed.diagnostics()["effective"]["solver"]["solver"] == solver, "the file keeps its solver"
    assert np.array_equal(resumed.terrain().heights, whole.terrain().heights)


def test_compare_reports_the_shared_metrics(hills):
    results = runnel.compare(hills, ["pipe", "olsen"], steps=20)
    assert set(results) == {"pipe", "olsen"}
    pipe, olsen = results["pipe"], results["olsen"]
    for values in (pipe, olsen):
        assert values["mass_balance"]["residual"] == 0.0
        assert values["steps"] == 20
    # The same initial terrain for both, and two models that erode it differently.
    assert pipe["hypsometric_integral_initial"] == olsen["hypsometric_integral_initial"]
    assert pipe["hypsometric_integral"] != olsen["hypsometric_integral"]


def test_bad_input_and_runtime_failures_are_told_apart(hills, tmp_path):
    with pytest.raises(runnel.InputError, match="pipe.rain"):
        runnel.Model("pipe", hills, {"pipe.rain": -1})
    with pytest.raises(runnel.InputError, match="no such file"):
        runnel.read_terrain(str(tmp_path / "missing.asc"))
    with pytest.raises(ValueError, match="unknown parameter"):
        runnel.Model("pipe", hills, {"pipe.no_such_key": 1})
    # A time step that must collapse: the failure of a run, not of its input.
    collapsing = runnel.Model("pipe", hills, {"pipe.rain": 50.0, "pipe.dt_min": 0.5})
    with pytest.raises(runnel.RunnelRuntimeError, match="time step collapsed"):
        for _ in range(200):
            collapsing.step()
    assert issubclass(runnel.RunnelRuntimeError, RuntimeError)
    assert not issubclass(runnel.InputError, RuntimeError)
