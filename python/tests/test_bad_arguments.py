# SPDX-License-Identifier: MIT
"""Every entry point refuses what it cannot use with runnel.InputError, and a coupling loop of a
million steps holds its memory flat."""
import resource

import numpy as np
import pytest

import runnel


@pytest.fixture(scope="module")
def flat():
    return runnel.Terrain(np.zeros((9, 9), dtype=np.float32), cell=1.0)


@pytest.mark.parametrize("dt", [float("nan"), float("inf"), -1.0, 1e13])
def test_advance_refuses_a_duration_that_is_not_one(flat, dt):
    model = runnel.Model("thermal", flat)
    with pytest.raises(runnel.InputError, match="dt"):
        model.advance(dt)
    assert model.steps == 0


def test_terrain_attributes_take_only_what_a_terrain_can_be(flat):
    t = runnel.Terrain(np.zeros((3, 3), dtype=np.float32), cell=2.0)
    for bad in (0.0, -1.0, float("nan"), 1e300):
        with pytest.raises(runnel.InputError, match="cell"):
            t.cell = bad
    assert t.cell == 2.0
    with pytest.raises(runnel.InputError, match="origin_x"):
        t.origin_x = float("nan")
    with pytest.raises(runnel.InputError, match="origin_z"):
        t.origin_z = 1e300
    with pytest.raises(runnel.InputError, match="cell"):
        runnel.Terrain(np.zeros((3, 3), dtype=np.float32), cell=float("inf"))
    with pytest.raises(runnel.InputError, match="heights"):
        runnel.Terrain(np.zeros((1, 3), dtype=np.float32))


def test_terrain_metrics_refuse_terrains_of_different_grids(flat):
    small = runnel.Terrain(np.zeros((5, 5), dtype=np.float32), cell=1.0)
    with pytest.raises(runnel.InputError, match="initial terrain"):
        runnel.terrain_metrics(flat, small)
    coarser = runnel.Terrain(np.zeros((9, 9), dtype=np.float32), cell=2.0)
    with pytest.raises(runnel.InputError, match="initial terrain"):
        runnel.terrain_metrics(flat, coarser)
    assert "hypsometric_integral" in runnel.terrain_metrics(flat, flat)


def _resident_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() / 1e6


@pytest.mark.parametrize("name", ["thermal", "olsen"])
def test_a_million_steps_from_python_hold_memory_flat(name):
    # A model whose step reads nothing back never waited for the device: its queue grew about
    # 2 KB a step, 2 GB over a million. Measured after a warm-up, so allocations of the first steps
    # (kernels, pools) do not count.
    hills = runnel.generate("fbm", 9, 9, 1.0, seed=3)
    model = runnel.Model(name, hills)
    for _ in range(20_000):
        model.step()
    before = _resident_mb()
    model.advance(1_000_000)
    grown = _resident_mb() - before
    assert model.steps == 1_020_000
    assert grown < 100, f"{name}: resident memory grew {grown:.0f} MB over a million steps"


@pytest.mark.parametrize("steps", [-1, 2**63, 1.5, True])
def test_compare_takes_a_whole_number_of_steps_that_ends(flat, steps):
    with pytest.raises(runnel.InputError, match="steps"):
        runnel.compare(flat, ["thermal"], steps)


@pytest.mark.parametrize("dtype", [complex, bool, object])
def test_a_terrain_is_made_of_real_numbers(dtype):
    with pytest.raises(runnel.InputError, match="real numbers"):
        runnel.Terrain(np.ones((5, 5), dtype=dtype), cell=1.0)


def test_heights_edited_beyond_what_readers_take_are_not_written(flat, tmp_path):
    t = runnel.Terrain(np.zeros((5, 5), dtype=np.float32), cell=1.0)
    t.heights[:] = 1e13
    with pytest.raises(runnel.InputError, match="1e\\+13"):
        runnel.write_terrain(str(tmp_path / "t.asc"), t)
    assert not (tmp_path / "t.asc").exists()


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -1.0])
def test_a_water_depth_is_a_finite_number_not_below_zero(flat, value):
    model = runnel.Model("pipe", flat)
    depth = np.zeros(81, dtype=np.float32)
    depth[5] = value
    with pytest.raises(runnel.InputError, match="surface_water__depth"):
        model.set_field("surface_water__depth", depth)
    assert np.all(model.field("surface_water__depth") == 0)


def test_a_model_is_the_one_named_whatever_params_say(flat):
    with pytest.raises(runnel.InputError, match="run.model"):
        runnel.Model("thermal", flat, {"run.model": "pipe"})
