# SPDX-License-Identifier: MIT
"""runnel from Python: erosion models on terrains, their fields as NumPy arrays, metrics.

    import runnel
    dem = runnel.read_terrain("dem.tif")             # GeoTIFF, ASC, PNG, NPY
    pipe = runnel.Model("pipe", dem, {"pipe.rain": 0.02})
    pipe.advance(60.0)                               # seconds (iteration models: iterations)
    depth = pipe.field("surface_water__depth")       # (ny, nx) float32
    print(pipe.mass_balance()["residual"])           # 0: exact

The C++ core does the work (runnel._runnel); this package is a thin layer. Errors carry the CLI's
one-line messages: InputError (a ValueError) for bad input, RunnelRuntimeError (a RuntimeError) for
a failure while running. docs/python.md has the whole API; runnel.bmi has the CSDMS BMI 2.0 class.
"""
import numbers

from ._runnel import (  # noqa: F401  (the public API)
    InputError,
    Model,
    RunnelRuntimeError,
    Terrain,
    __version__,
    generate,
    generator_names,
    model_names,
    read_terrain,
    terrain_metrics,
    write_terrain,
)

def _from_landlab(grid, field="topographic__elevation"):
    from .landlab import terrain_from_landlab

    return terrain_from_landlab(grid, field)


def _to_landlab(self, field="topographic__elevation"):
    from .landlab import terrain_to_landlab

    return terrain_to_landlab(self, field)


_from_landlab.__doc__ = """A Terrain of a Landlab RasterModelGrid's node field (runnel.landlab).

Parameters
----------
grid : landlab.RasterModelGrid
    Square cells; rows counted northwards, as Landlab has them.
field : str, optional
    The node field of heights (default topographic__elevation).

Returns
-------
Terrain
"""
_to_landlab.__doc__ = """A Landlab RasterModelGrid with the heights as a node field (runnel.landlab).

Parameters
----------
field : str, optional
    The node field to create (default topographic__elevation).

Returns
-------
landlab.RasterModelGrid
"""
def _to_xarray(self):
    from .xarray import model_to_xarray

    return model_to_xarray(self)


_to_xarray.__doc__ = """The model's state now as an xarray Dataset (runnel.xarray; the conventions of
``runnel export --format netcdf``: CF-1.8, x and y at the pixels' centres, spatial_ref).

Returns
-------
xarray.Dataset
"""
Model.to_xarray = _to_xarray
Terrain.from_landlab = staticmethod(_from_landlab)
Terrain.to_landlab = _to_landlab

__all__ = [
    "InputError",
    "Model",
    "RunnelRuntimeError",
    "Terrain",
    "compare",
    "generate",
    "generator_names",
    "model_names",
    "read_terrain",
    "terrain_metrics",
    "write_terrain",
]


def compare(terrain, models, steps, params=None):
    """Runs several models on one terrain and compares them, as ``runnel compare`` reports them.

    Parameters
    ----------
    terrain : Terrain
    models : list of str
        Model names (model_names()).
    steps : int
        Steps each model takes.
    params : dict, optional
        Parameter keys and values (docs/parameters.md), for every model.

    Returns
    -------
    dict
        {name: metrics}: the shared terrain metrics of docs/metrics.md, the mass balance, steps and
        model time.
    """
    # A whole number of steps that ends: bool is an int, a float 1e3 is not a count.
    if isinstance(steps, bool) or not isinstance(steps, numbers.Integral) or not 0 <= steps <= 10**12:
        raise InputError(f"compare: steps must be a whole number from 0 to 1e12 (got {steps!r})")
    results = {}
    for name in models:
        model = Model(name, terrain, params or {})
        for _ in range(steps):
            model.step()
        values = terrain_metrics(model.initial_terrain(), model.terrain())
        values["mass_balance"] = model.mass_balance()
        values["steps"] = model.steps
        values["time"] = model.time
        results[name] = values
    return results
