# SPDX-License-Identifier: MIT
"""runnel with Landlab, the real client: terrains to and from a RasterModelGrid, the RunnelStorm
component in a Landlab loop, and runnel's pipe and SPH models coupled through BMI with Landlab's
LinearDiffuser and uplift for several cycles, the volume bookkeeping checked exactly."""
import numpy as np
import pytest

landlab = pytest.importorskip("landlab", reason="Landlab is not installed (scripts/setup-python.sh)")
pytest.importorskip("bmipy", reason="bmipy is not installed (scripts/setup-python.sh)")
from landlab import RasterModelGrid  # noqa: E402
from landlab.components import LinearDiffuser  # noqa: E402

import runnel  # noqa: E402
from runnel.bmi import RunnelBmi  # noqa: E402
from runnel.landlab import RunnelStorm  # noqa: E402

QUANTUM = 1e-6  # erosion.height_quantum's default


def sloping_grid():
    """A grid whose nodes rise northwards (y) and a little eastwards (x): any flip shows."""
    grid = RasterModelGrid((9, 7), xy_spacing=2.0, xy_of_lower_left=(500.0, 1000.0))
    z = grid.add_field("topographic__elevation", 0.5 * (grid.y_of_node - 1000.0) + 0.1 * (grid.x_of_node - 500.0),
                       at="node")
    return grid, z


def test_a_terrain_from_landlab_keeps_north_up_and_the_pixel_centres():
    grid, z = sloping_grid()
    terrain = runnel.Terrain.from_landlab(grid)
    assert (terrain.ny, terrain.nx, terrain.cell) == (9, 7, 2.0)
    # runnel's row 0 is the northern row: Landlab's last.
    assert np.array_equal(terrain.heights[0], z.reshape(9, 7)[-1].astype(np.float32))
    assert terrain.heights[0, 0] > terrain.heights[-1, 0], "north is higher"
    # The raster's lower-left corner is half a cell south-west of Landlab's first node.
    assert (terrain.origin_x, terrain.origin_z) == (499.0, 999.0)
    back = terrain.to_landlab()
    assert tuple(back.xy_of_lower_left) == (500.0, 1000.0)
    assert back.shape == grid.shape and back.dx == grid.dx
    assert np.allclose(back.at_node["topographic__elevation"], z, atol=1e-5)


def test_a_model_on_a_landlab_terrain_reads_its_rows_as_landlab_does():
    grid, z = sloping_grid()
    model = runnel.Model("thermal", runnel.Terrain.from_landlab(grid))
    bmi_order = np.flipud(model.elevation()).reshape(-1)
    assert np.allclose(bmi_order, z, atol=1e-5), "node k of Landlab is node k of runnel's BMI"


def test_a_landlab_dem_in_double_precision_starts_a_model_exact_to_the_quantum():
    """A 65² DEM a kilometre high: float32 holds such heights to about 6e-5 m, sixty quanta, so the
    model starts from Landlab's float64 heights themselves, each within half a quantum, and the
    volume equals Landlab's own sum to the quantum."""
    grid = RasterModelGrid((65, 65), xy_spacing=30.0)
    rng = np.random.default_rng(7)
    z = grid.add_field("topographic__elevation", 1000.0 + 400.0 * rng.random(grid.number_of_nodes),
                       at="node")
    assert np.max(np.abs(z.astype(np.float32) - z)) > 10 * QUANTUM, "float32 would lose these heights"
    model = runnel.Model("thermal", runnel.Terrain.from_landlab(grid))
    start = np.flipud(model.elevation()).reshape(-1)
    assert np.array_equal(quanta(start), quanta(z)), "each node Landlab's height rounded to the quantum"
    # The volumes then differ by the nodes' rounding alone: 0.006 m³ here (1.76 m³ through float32).
    gap = abs(start.sum() - z.sum()) * grid.dx * grid.dy
    assert gap < 0.02, f"{gap} m³ from Landlab's volume"
    # A height edited through the float32 view is the height the model takes there.
    terrain = runnel.Terrain.from_landlab(grid)
    terrain.heights[0, 0] = 5.0
    assert runnel.Model("thermal", terrain).elevation()[0, 0] == 5.0


def fbm_grid(size=33, cell=2.0):
    terrain = runnel.generate("fbm", size, size, cell, seed=4, params={"relief": 0.3})
    return terrain.to_landlab()


def quanta(values):
    return np.round(np.asarray(values) / QUANTUM).astype(np.int64)


def test_runnel_storm_runs_in_a_landlab_loop_with_creep_and_uplift():
    grid = fbm_grid()
    z = grid.at_node["topographic__elevation"]
    storm = RunnelStorm(grid, model="pipe", params={"pipe.rain": 0.02})
    diffuser = LinearDiffuser(grid, linear_diffusivity=0.05)
    imposed = 0
    for _ in range(4):
        storm.run_one_step(1.0)
        assert np.any(grid.at_node["surface_water__depth"] > 0), "the storm's water comes back"
        after_storm = quanta(z)
        diffuser.run_one_step(50.0)
        z[grid.core_nodes] += 0.002  # uplift
        imposed += int((quanta(z) - after_storm).sum())
    storm.run_one_step(1.0)  # takes the last cycle's change in
    balance = storm.model.mass_balance()
    assert balance["imposed"] == pytest.approx(imposed * QUANTUM * 4.0, rel=1e-12)
    assert balance["residual_quanta"] == 0
    assert balance["eroded"] > 0
    assert storm.model.time == pytest.approx(5.0, rel=1e-12)


SCENARIOS = {
    "pipe": """
[run]
model = "pipe"
sim_time = 10.0
[terrain]
generator = "fbm"
size = 33
cell = 2.0
[pipe]
rain = 0.02
""",
    "sph": """
[run]
model = "sph"
sim_time = 10.0
[terrain]
generator = "fbm"
size = 33
cell = 2.0
[rain]
intensity = 7200.0
max_particles = 4000
[erosion]
morphological_factor = 100.0
""",
}


@pytest.mark.parametrize("model", ["pipe", "sph"])
def test_bmi_couples_with_landlab_creep_and_uplift_exactly(scenario, model):
    bmi = RunnelBmi()
    bmi.initialize(str(scenario(SCENARIOS[model])))
    shape = tuple(bmi.get_grid_shape(0, np.empty(2, dtype=int)))
    spacing = bmi.get_grid_spacing(0, np.empty(2))
    origin = bmi.get_grid_origin(0, np.empty(2))
    # Landlab's grid from BMI's description alone: (rows, columns), (dy, dx), (y, x) of node 0.
    grid = RasterModelGrid(shape, xy_spacing=(spacing[1], spacing[0]), xy_of_lower_left=(origin[1], origin[0]))
    z = grid.add_field("topographic__elevation", bmi.get_value("topographic__elevation", np.empty(grid.number_of_nodes)),
                       at="node")
    # The grid and the model agree on which node is where: the north-east vertex of runnel's own
    # terrain is Landlab's last node.
    assert z[-1] == bmi.model.elevation()[0, -1]
    diffuser = LinearDiffuser(grid, linear_diffusivity=0.05)
    imposed, t = 0, 0.0
    for _ in range(3):
        t += 2.0
        bmi.update_until(t)
        bmi.get_value("topographic__elevation", z)
        after_storm = quanta(z)
        diffuser.run_one_step(50.0)
        z[grid.core_nodes] += 0.002
        bmi.set_value("topographic__elevation", z)
        imposed += int((quanta(z) - after_storm).sum())
        balance = bmi.model.mass_balance()
        assert balance["imposed"] == pytest.approx(imposed * QUANTUM * 4.0, rel=1e-12)
        assert balance["residual_quanta"] == 0, "erosion, transport and the imposed change balance"
    assert bmi.get_current_time() == pytest.approx(6.0, rel=1e-12)
    assert bmi.model.mass_balance()["eroded"] > 0
    # The uplift raised the interior: what runnel holds is Landlab's last state, to the quantum.
    assert np.array_equal(bmi.get_value("topographic__elevation", np.empty(grid.number_of_nodes)),
                          quanta(z) * QUANTUM)
    bmi.finalize()


def test_landlab_nodata_nodes_are_holes_not_pits():
    """Closed nodes (Landlab's NODATA) are filled from their neighbours and kept as holes."""
    grid, z = sloping_grid()
    z[grid.nodes[4, 3]] = -9999.0
    grid.status_at_node[grid.nodes[4, 3]] = grid.BC_NODE_IS_CLOSED
    terrain = runnel.Terrain.from_landlab(grid)
    assert terrain.nodata == -9999.0
    h = terrain.heights[9 - 1 - 4, 3]
    neighbours = z.reshape(9, 7)[3:6, 2:5]
    assert neighbours[neighbours > -9999].min() <= h <= neighbours.max(), "filled, not a pit"


def test_a_grid_that_is_not_a_raster_is_refused_by_name():
    from landlab import HexModelGrid

    with pytest.raises(runnel.InputError, match="HexModelGrid"):
        runnel.Terrain.from_landlab(HexModelGrid((5, 5)))
