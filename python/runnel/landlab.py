# SPDX-License-Identifier: MIT
"""runnel in a Landlab model: terrains to and from a RasterModelGrid, and RunnelStorm, a Landlab
component that runs one of runnel's models on the grid's topography.

    from landlab import RasterModelGrid
    from landlab.components import LinearDiffuser
    from runnel.landlab import RunnelStorm

    grid = RasterModelGrid((65, 65), xy_spacing=2.0)
    z = grid.add_zeros("topographic__elevation", at="node")
    ...
    storm = RunnelStorm(grid, model="pipe", params={"pipe.rain": 0.01})
    diffuser = LinearDiffuser(grid, linear_diffusivity=0.01)
    for _ in range(10):
        storm.run_one_step(60.0)     # a minute of rain (the model's clock: s for pipe and sph)
        diffuser.run_one_step(1e4)   # hillslope creep between storms

Orientation: Landlab counts node rows northwards from the south-west node at xy_of_lower_left;
runnel's terrains keep row 0 the northern row, and their origin is the raster's lower-left pixel
corner, half a cell south-west of that node. The functions here convert both ways exactly.
"""
import numpy as np

from . import InputError, Model, Terrain
from ._runnel import _terrain_with_holes

_ELEVATION = "topographic__elevation"


def terrain_from_landlab(grid, field=_ELEVATION):
    """A runnel Terrain of a Landlab RasterModelGrid's node field.

    Parameters
    ----------
    grid : landlab.RasterModelGrid
        A raster grid with square cells (dx == dy).
    field : str, optional
        The node field of heights, m (default topographic__elevation).

    Returns
    -------
    Terrain
        Row 0 the grid's northern row; origin_x, origin_z the raster's lower-left corner.
    """
    from landlab import RasterModelGrid

    if not isinstance(grid, RasterModelGrid):
        raise InputError(
            f"grid: a {type(grid).__name__}; runnel's terrains are rasters (a RasterModelGrid)"
        )
    dy, dx = (float(s) for s in grid.spacing)
    if dx != dy:
        raise InputError(f"grid: cells of {dx} x {dy} m; runnel's terrains have square cells")
    heights = np.flipud(np.asarray(grid.at_node[field], dtype=np.float64).reshape(grid.shape))
    # Closed nodes (Landlab's NODATA, e.g. set_nodata_nodes_to_closed) are holes, filled from their
    # neighbours and written back as NODATA, as runnel reads a raster's NODATA cells.
    closed = np.flipud(
        (np.asarray(grid.status_at_node) == grid.BC_NODE_IS_CLOSED).reshape(grid.shape)
    )
    if closed.any():
        terrain = _terrain_with_holes(heights, dx, closed, -9999.0)
    else:
        terrain = Terrain(heights, dx)
    x0, y0 = (float(v) for v in grid.xy_of_lower_left)
    terrain.origin_x = x0 - 0.5 * dx
    terrain.origin_z = y0 - 0.5 * dx
    return terrain


def terrain_to_landlab(terrain, field=_ELEVATION):
    """A Landlab RasterModelGrid holding a runnel Terrain's heights as a node field.

    Parameters
    ----------
    terrain : Terrain
    field : str, optional
        The node field to create (default topographic__elevation), float64, m.

    Returns
    -------
    landlab.RasterModelGrid
        (ny, nx) nodes, xy_of_lower_left the south-west vertex's pixel centre.
    """
    from landlab import RasterModelGrid

    grid = RasterModelGrid((terrain.ny, terrain.nx), xy_spacing=terrain.cell,
                           xy_of_lower_left=(terrain.origin_x + 0.5 * terrain.cell,
                                             terrain.origin_z + 0.5 * terrain.cell))
    grid.add_field(field, np.flipud(terrain.heights).astype(np.float64).reshape(-1), at="node")
    return grid


def _make_runnel_storm():
    from landlab import Component

    class RunnelStorm(Component):
        """A storm of one of runnel's erosion models on a Landlab grid's topography.

        Each run_one_step(dt) takes the grid's topographic__elevation as it is now (other
        components may have changed it: runnel books that as an imposed change in its mass
        balance, exactly), advances runnel's model by dt in its clock (s for "pipe" and "sph",
        yr for "stream-power", iterations otherwise) and writes the eroded topography back, with
        the water depth where the model has one.

        Parameters
        ----------
        grid : landlab.RasterModelGrid
            Square cells; its topographic__elevation node field, m.
        model : str, optional
            A runnel model (runnel.model_names(); default "pipe").
        params : dict, optional
            runnel parameters (docs/parameters.md), e.g. {"pipe.rain": 0.01}.
        device : str, optional
            The OpenCL device.
        """

        _name = "RunnelStorm"
        _unit_agnostic = False
        _info = {
            _ELEVATION: {
                "dtype": float, "intent": "inout", "optional": False, "units": "m",
                "mapping": "node", "doc": "Land surface topographic elevation",
            },
            "surface_water__depth": {
                "dtype": float, "intent": "out", "optional": True, "units": "m",
                "mapping": "node", "doc": "Depth of the water on the surface (grid models)",
            },
        }

        def __init__(self, grid, model="pipe", params=None, device=""):
            super().__init__(grid)
            self._model = Model(model, terrain_from_landlab(grid), dict(params or {}), device)
            self._has_depth = "surface_water__depth" in self._model.field_names()
            if self._has_depth and "surface_water__depth" not in grid.at_node:
                grid.add_zeros("surface_water__depth", at="node")

        @property
        def model(self):
            """The runnel.Model (its mass balance, time, checkpoints)."""
            return self._model

        def run_one_step(self, dt):
            """Advances runnel's model by dt (its clock's units) on the grid's topography."""
            shape = self._grid.shape
            z = self._grid.at_node[_ELEVATION]
            self._model.set_elevation(np.flipud(np.asarray(z, dtype=np.float64).reshape(shape)))
            self._model.advance(dt)
            z[:] = np.flipud(self._model.elevation()).reshape(-1)
            if self._has_depth:
                depth = self._model.field("surface_water__depth")
                self._grid.at_node["surface_water__depth"][:] = np.flipud(depth).reshape(-1)

    return RunnelStorm


def __getattr__(name):
    # RunnelStorm is built on first use, so this module imports without Landlab.
    if name == "RunnelStorm":
        storm = _make_runnel_storm()
        globals()["RunnelStorm"] = storm
        return storm
    raise AttributeError(name)
