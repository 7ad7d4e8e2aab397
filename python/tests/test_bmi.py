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


def test_variables_carry_standard_names_udunits_units_and_landlab_aliases(bmi):
    outputs = bmi.get_output_var_names()
    assert "land_surface__elevation" in outputs and "land_surface_water__depth" in outputs
    assert not any("quanta" in bmi.get_var_units(name) for name in outputs)
    assert bmi.get_output_item_count() == len(outputs)
    inputs = bmi.get_input_var_names()
    assert set(inputs) == {"land_surface__elevation", "land_surface_water__depth"}
    assert bmi.get_input_item_count() == len(inputs)
    # The pipe model's 2-component velocity and 4-component outflux become scalars on the nodes.
    assert "land_surface_water_flowing__north_component_of_velocity" in outputs
    assert "land_surface_water~outgoing~south__volume_flow_rate" in outputs
    for name in outputs:
        value = bmi.get_value(name, np.empty(bmi.get_var_nbytes(name) // bmi.get_var_itemsize(name),
                                             dtype=bmi.get_var_type(name)))
        assert value.dtype == np.dtype(bmi.get_var_type(name))
        assert bmi.get_var_nbytes(name) == value.nbytes == bmi.get_grid_size(0) * value.itemsize
        assert bmi.get_var_location(name) == "node"
        assert bmi.get_var_grid(name) == 0
    assert bmi.get_var_units("land_surface__elevation") == "m"
    assert bmi.get_var_type("land_surface__elevation") == "float64", "exact heights"
    assert bmi.get_var_units("land_surface_water~outgoing~west__volume_flow_rate") == "m3 s-1"
    assert bmi.get_var_units("land_surface_water_sediment~suspended__thickness") == "m"
    # Landlab's names are aliases of the same values.
    both = [bmi.get_value(n, np.empty(33 * 33)) for n in ("land_surface__elevation", "topographic__elevation")]
    assert np.array_equal(*both)
    with pytest.raises(ValueError):
        bmi.get_var_units("no_such__variable")


def test_the_names_are_valid_csdms_standard_names(bmi):
    standard_names = pytest.importorskip("standard_names", reason="standard_names comes with bmi-tester")
    for name in bmi.get_output_var_names():
        assert standard_names.StandardName(name).name == name


def test_the_units_are_udunits_units_the_tester_accepts(bmi):
    api = pytest.importorskip("bmi_tester.api", reason="bmi-tester is not installed")
    assert api.WITH_GIMLI_UNITS, "gimli.units 0.3 is installed, so bmi-tester checks units"
    for name in bmi.get_output_var_names():
        assert api.check_unit_is_valid(bmi.get_var_units(name)), name
    assert api.check_unit_is_time(bmi.get_time_units())


def test_the_grid_counts_rows_northwards_from_the_south_west_pixel_centre(bmi):
    assert bmi.get_grid_type(0) == "uniform_rectilinear"
    assert bmi.get_grid_rank(0) == 2
    shape = bmi.get_grid_shape(0, np.empty(2, dtype=int))
    assert tuple(shape) == (33, 33)
    assert bmi.get_grid_size(0) == 33 * 33 == bmi.get_grid_node_count(0)
    assert tuple(bmi.get_grid_spacing(0, np.empty(2))) == (2.0, 2.0)
    origin = bmi.get_grid_origin(0, np.empty(2))
    assert tuple(origin) == (1.0, 1.0), "(y, x) of the south-west vertex, half a cell in"
    elevation = bmi.get_value("land_surface__elevation", np.empty(33 * 33)).reshape(33, 33)
    heights = bmi.model.elevation()  # runnel's own order: row 0 the northern row
    assert np.array_equal(elevation[0], heights[-1]), "BMI row 0 is the southern row"
    assert np.array_equal(elevation, np.flipud(heights))
    for unstructured in ("get_grid_edge_count", "get_grid_face_count"):
        with pytest.raises(NotImplementedError):
            getattr(bmi, unstructured)(0)


def test_set_elevation_is_an_exact_external_source(bmi):
    bmi.update_until(1.0)
    z = bmi.get_value("topographic__elevation", np.empty(33 * 33))
    bmi.set_value("topographic__elevation", z)
    assert bmi.model.mass_balance()["imposed"] == 0.0, "the heights read back are exact"
    uplifted = z.copy()
    uplifted.reshape(33, 33)[1:-1, 1:-1] += 0.01  # uplift of the interior
    bmi.set_value("topographic__elevation", uplifted)
    balance = bmi.model.mass_balance()
    assert balance["imposed"] == pytest.approx(31 * 31 * 0.01 * 2.0 * 2.0, rel=1e-9)
    assert balance["residual_quanta"] == 0
    assert np.array_equal(bmi.get_value("topographic__elevation", np.empty(33 * 33)),
                          np.round(uplifted / 1e-6) * 1e-6)
    bmi.update_until(2.0)
    assert bmi.model.mass_balance()["residual_quanta"] == 0


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
    depth = bmi.get_value_ptr("surface_water__depth")  # Landlab's name for land_surface_water__depth
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
        bmi.set_value("land_surface_water_sediment~suspended__thickness", np.zeros(depth.size))
    bmi.update()  # the model goes on from the water it was given
    assert np.all(np.isfinite(bmi.get_value("surface_water__depth", np.empty_like(depth))))


def test_stream_power_counts_years_to_its_own_end(scenario):
    bmi = RunnelBmi()
    bmi.initialize(str(scenario(PIPE.replace('model = "pipe"', 'model = "stream-power"')
                                .replace("sim_time = 3.0", "sim_years = 50000.0"))))
    assert bmi.get_time_units() == "yr" and bmi.get_end_time() == 50000.0
    bmi.update()
    assert bmi.get_current_time() == bmi.get_time_step() > 1.0, "a step of years, not 1"
    bmi.update_until(2500.0)
    assert bmi.get_current_time() == 2500.0, "the last step shortened to land on the target"
    assert bmi.model.mass_balance()["residual_quanta"] == 0
    bmi.finalize()


def test_sph_takes_a_rain_field(scenario):
    bmi = RunnelBmi()
    bmi.initialize(str(scenario(PIPE.replace('model = "pipe"', 'model = "sph"')
                                .replace("[pipe]\nrain = 0.02", "[rain]\nintensity = 3600.0"))))
    name = "atmosphere_rainfall_water__volume_flux"
    assert name in bmi.get_input_var_names() and bmi.get_var_units(name) == "m s-1"
    rain = bmi.get_value(name, np.empty(33 * 33, dtype=np.float32))
    assert np.allclose(rain, 1e-3), "the scenario's 3600 mm/h everywhere"
    south = np.zeros((33, 33), dtype=np.float32)
    south[:8] = 2e-3  # BMI rows 0-7: the southern quarter
    bmi.set_value("rainfall__flux", south.reshape(-1))
    assert np.allclose(bmi.get_value(name, np.empty(33 * 33, dtype=np.float32)), south.reshape(-1))
    bmi.update_until(2.0)
    z = bmi.model.field("particle__position")[:, 2]  # runnel's z counts southwards from row 0
    assert z.size > 0 and np.all(z > 0.7 * 32 * 2.0), "every drop fell on the southern quarter"
    bmi.finalize()


def test_an_iteration_model_counts_iterations(scenario):
    bmi = RunnelBmi()
    bmi.initialize(str(scenario(PIPE.replace('model = "pipe"', 'model = "olsen"')
                                .replace("sim_time = 3.0", "iterations = 5"))))
    assert bmi.get_time_units() == "1" and bmi.get_end_time() == 5.0
    bmi.update_until(5.0)
    assert bmi.get_current_time() == 5.0
    bmi.finalize()


SCENARIOS_FOR_THE_TESTER = {
    "pipe": PIPE,
    "sph": PIPE.replace('model = "pipe"', 'model = "sph"').replace("[pipe]\nrain = 0.02", "[rain]\nintensity = 3600.0"),
    "sph-dfsph": PIPE.replace('model = "pipe"', 'model = "sph"')
                     .replace("[pipe]\nrain = 0.02", '[rain]\nintensity = 3600.0\n[sph]\nsolver = "dfsph"'),
    "stream-power": PIPE.replace('model = "pipe"', 'model = "stream-power"').replace("sim_time = 3.0", "sim_years = 5000.0"),
}


@pytest.mark.skipif(shutil.which("bmi-test") is None and
                    subprocess.run([sys.executable, "-c", "import bmi_tester"]).returncode != 0,
                    reason="bmi-tester is not installed (scripts/setup-python.sh installs it)")
@pytest.mark.parametrize("model", sorted(SCENARIOS_FOR_THE_TESTER))
def test_bmi_tester_passes_with_its_units_check(scenario, tmp_path, model):
    import os

    import runnel

    from bmi_tester.api import WITH_GIMLI_UNITS
    assert WITH_GIMLI_UNITS, "gimli.units 0.3 installed: the tester checks every unit"
    config = scenario(SCENARIOS_FOR_THE_TESTER[model])
    # The package as imported here, whatever the working directory of the tester. (The tester's own
    # pytest puts site-packages first on sys.path: it tests the installed package.)
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(runnel.__file__))))
    r = subprocess.run([sys.executable, "-m", "bmi_tester", "runnel.bmi:RunnelBmi",
                        "--config-file", config.name, "--root-dir", str(tmp_path), "--quiet"],
                       capture_output=True, text=True, timeout=600, cwd=tmp_path, env=env)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-2000:]
    assert " passed" in r.stdout and " failed" not in r.stdout
