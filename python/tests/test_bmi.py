# SPDX-License-Identifier: MIT
"""runnel.bmi.RunnelBmi against the BMI 2.0 contract: every function, checked on a pipe model
(grid fields, a clock in seconds) and an Olsen model (iterations), and bmi-tester where installed."""
import shutil
import subprocess
import sys

import numpy as np
import pytest

bmipy = pytest.importorskip("bmipy", reason="bmipy is not installed (scripts/setup-python.sh)")
from runnel.bmi import RunnelBmi  # noqa: E402

PIPE = """
[run]
model = "pipe"
sim_time = 3.0
[terrain]
generator = "fbm"
size = 33
cell = 2.0
[pipe]
rain = 0.02
"""


@pytest.fixture
def bmi(scenario):
    component = RunnelBmi()
    component.initialize(str(scenario(PIPE)))
    yield component
    component.finalize()


def test_it_is_a_bmipy_component(bmi):
    assert isinstance(bmi, bmipy.Bmi)
    assert "pipe" in bmi.get_component_name()


def test_variables_are_the_models_vertex_fields(bmi):
    outputs = bmi.get_output_var_names()
    assert "topographic__elevation" in outputs and "surface_water__depth" in outputs
    assert bmi.get_output_item_count() == len(outputs)
    inputs = bmi.get_input_var_names()
    assert "surface_water__depth" in inputs and "topographic__elevation" not in inputs
    assert bmi.get_input_item_count() == len(inputs)
    for name in outputs:
        value = bmi.get_value(name, np.empty(bmi.get_var_nbytes(name) // bmi.get_var_itemsize(name),
                                             dtype=bmi.get_var_type(name)))
        assert value.dtype == np.dtype(bmi.get_var_type(name))
        assert bmi.get_var_nbytes(name) == value.nbytes
        assert bmi.get_var_location(name) == "node"
        assert bmi.get_var_grid(name) == 0
    assert bmi.get_var_units("topographic__elevation") == "m"
    assert bmi.get_var_units("surface_water__depth") == "m"
    with pytest.raises(ValueError):
        bmi.get_var_units("no_such__variable")


def test_the_grid_is_the_terrains_uniform_rectilinear_grid(bmi):
    assert bmi.get_grid_type(0) == "uniform_rectilinear"
    assert bmi.get_grid_rank(0) == 2
    shape = bmi.get_grid_shape(0, np.empty(2, dtype=int))
    assert tuple(shape) == (33, 33)
    assert bmi.get_grid_size(0) == 33 * 33 == bmi.get_grid_node_count(0)
    assert tuple(bmi.get_grid_spacing(0, np.empty(2))) == (2.0, 2.0)
    origin = bmi.get_grid_origin(0, np.empty(2))
    assert tuple(origin) == (32 * 2.0, 0.0), "the north-west vertex, (row, column) order"
    elevation = bmi.get_value("topographic__elevation", np.empty(33 * 33, dtype=np.float32))
    assert elevation.size == bmi.get_grid_size(0)
    for unstructured in ("get_grid_edge_count", "get_grid_face_count"):
        with pytest.raises(NotImplementedError):
            getattr(bmi, unstructured)(0)


def test_time_advances_with_update_and_update_until(bmi):
    assert bmi.get_start_time() == 0.0 == bmi.get_current_time()
    assert bmi.get_end_time() == 3.0
    assert bmi.get_time_units() == "s"
    bmi.update()
    first = bmi.get_current_time()
    assert first > 0 and bmi.get_time_step() > 0
    # The model's own next step (the pipe model's CFL limit), not a fixed 1.
    assert bmi.get_time_step() != 1.0 and bmi.get_time_step() <= 0.05
    bmi.update_until(1.0)
    assert bmi.get_current_time() == pytest.approx(1.0, rel=1e-12), "lands on the target"
    bmi.update_until(2.0)
    assert bmi.get_current_time() == pytest.approx(2.0, rel=1e-12)
    with pytest.raises(ValueError):
        bmi.update_until(0.5)


def test_value_pointers_follow_updates_and_values_can_be_set(bmi):
    depth = bmi.get_value_ptr("surface_water__depth")
    before = depth.copy()
    bmi.update_until(1.0)
    assert depth is bmi.get_value_ptr("surface_water__depth")
    assert not np.array_equal(depth, before), "refreshed in place by update"
    fresh = bmi.get_value("surface_water__depth", np.empty_like(depth))
    assert np.array_equal(depth, fresh)

    picked = bmi.get_value_at_indices("surface_water__depth", np.empty(3, dtype=np.float32), [0, 5, 7])
    assert np.array_equal(picked, fresh[[0, 5, 7]])
    bmi.set_value("surface_water__depth", np.full(depth.size, 0.25, dtype=np.float32))
    assert np.all(bmi.get_value("surface_water__depth", np.empty_like(depth)) == 0.25)
    bmi.set_value_at_indices("surface_water__depth", np.array([3]), np.array([1.5], dtype=np.float32))
    assert bmi.get_value("surface_water__depth", np.empty_like(depth))[3] == 1.5
    with pytest.raises(ValueError, match="output"):
        bmi.set_value("topographic__elevation", np.zeros(depth.size, dtype=np.float32))
    bmi.update()  # the model goes on from the water it was given
    assert np.all(np.isfinite(bmi.get_value("surface_water__depth", np.empty_like(depth))))


def test_an_iteration_model_counts_iterations(scenario):
    bmi = RunnelBmi()
    bmi.initialize(str(scenario(PIPE.replace('model = "pipe"', 'model = "olsen"')
                                .replace("sim_time = 3.0", "iterations = 5"))))
    assert bmi.get_time_units() == "1" and bmi.get_end_time() == 5.0
    bmi.update_until(5.0)
    assert bmi.get_current_time() == 5.0
    bmi.finalize()


@pytest.mark.skipif(shutil.which("bmi-test") is None and
                    subprocess.run([sys.executable, "-c", "import bmi_tester"]).returncode != 0,
                    reason="bmi-tester is not installed (scripts/setup-python.sh installs it)")
def test_bmi_tester_passes(scenario, tmp_path):
    import os

    import runnel

    config = scenario(PIPE)
    # The package as imported here, whatever the working directory of the tester.
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(runnel.__file__))))
    r = subprocess.run([sys.executable, "-m", "bmi_tester", "runnel.bmi:RunnelBmi",
                        "--config-file", config.name, "--root-dir", str(tmp_path), "--quiet"],
                       capture_output=True, text=True, timeout=600, cwd=tmp_path, env=env)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-2000:]
    assert " passed" in r.stdout and " failed" not in r.stdout
