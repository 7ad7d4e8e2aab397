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
    """Runs each of ``models`` on ``terrain`` for ``steps`` steps with ``params`` (a dict of
    parameter keys, docs/parameters.md) and returns {name: metrics}: the shared terrain metrics of
    docs/metrics.md, the mass balance, steps and model time, as `runnel compare` reports them."""
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
