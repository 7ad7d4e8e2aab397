# SPDX-License-Identifier: MIT
"""The BMI's variables: CSDMS Standard Names (Landlab's names as aliases), their units (UDUNITS),
and how each is read from, and written to, a runnel model's fields.

Every array the BMI hands out is in BMI's order for a uniform rectilinear grid: row 0 is the
southern row (rows counted northwards, as in Landlab), while runnel's own fields keep row 0 the
northern row of the terrain files. A field of several components becomes one scalar variable a
component (the BMI's values are scalars on nodes).
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Variable:
    """One BMI variable: a scalar on every node of the terrain's grid."""

    name: str  # the CSDMS Standard Name (or runnel's name where the registry has none)
    alias: str  # the name Landlab uses, also accepted
    field: str  # the runnel field it comes from (docs/fields.md)
    units: str  # UDUNITS
    dtype: str = "float32"
    component: int = -1  # the field's component (-1: a scalar field)
    sign: float = 1.0  # runnel's z axis points south: a northward component is −z
    input: bool = False  # a coupler may set it

    def read(self, model, quantum):
        """The variable's values as BMI gives them: flat, row 0 the southern row."""
        if self.field == "topographic__elevation":
            values = model.elevation()
        elif self.field == _RAIN:
            values = _rain_rates(model)
        else:
            values = model.field(self.field)
            if self.component >= 0:
                values = values[:, :, self.component]
            if values.dtype == np.int64:  # counts of the height quantum
                values = values * quantum
            values = self.sign * values if self.sign != 1.0 else values
        return np.flipud(values).astype(self.dtype, copy=False).reshape(-1)

    def write(self, model, flat):
        """Sets the variable from BMI's flat values (row 0 the southern row)."""
        grid = model.initial_terrain()
        values = np.flipud(np.asarray(flat).reshape(grid.ny, grid.nx))
        if self.field == "topographic__elevation":
            model.set_elevation(values.astype(np.float64))
        elif self.field == _RAIN:
            model.set_rain_rates(values.astype(np.float32))
        else:
            model.set_field(self.field, values.astype(np.float32))


_RAIN = "rain_rate"  # not a stored field: the scenario's rain rate times the rain mask


def _rain_rates(model):
    """The rain at every vertex: the scenario's rate times the rain mask a coupler or the scenario
    set (everywhere the scenario's rate until then)."""
    grid = model.initial_terrain()
    rate = np.float32(model.rain_rate)
    try:
        return model.field("ground__rain_mask") * rate
    except ValueError:  # no mask
        return np.full((grid.ny, grid.nx), rate, dtype=np.float32)


# The water's outflow to the four neighbours (the pipe model's surface_water__outflux components:
# left, right, top = north, bottom = south).
_OUTFLUX = [
    Variable(f"land_surface_water~outgoing~{side}__volume_flow_rate", f"surface_water__outflux_{side}",
             "surface_water__outflux", "m3 s-1", component=k)
    for k, side in enumerate(("west", "east", "north", "south"))
]

VARIABLES = [
    Variable("land_surface__elevation", "topographic__elevation", "topographic__elevation", "m",
             dtype="float64", input=True),
    Variable("land_surface_water__depth", "surface_water__depth", "surface_water__depth", "m",
             input=True),
    Variable("land_surface_water_sediment~suspended__thickness", "sediment__suspended",
             "sediment__suspended", "m", dtype="float64"),
    Variable("land_surface_water_flowing__east_component_of_velocity", "surface_water__velocity_x",
             "surface_water__velocity", "m s-1", component=0),
    Variable("land_surface_water_flowing__north_component_of_velocity", "surface_water__velocity_y",
             "surface_water__velocity", "m s-1", component=1, sign=-1.0),
    *_OUTFLUX,
    Variable("land_surface_sediment__thickness", "ground__sediment_thickness",
             "ground__sediment_thickness", "m", dtype="float64"),
    Variable("atmosphere_rainfall_water__volume_flux", "rainfall__flux", _RAIN, "m s-1",
             input=True),
]


def variables_of(model):
    """The variables a model has: those of its vertex fields, and the rain field where it takes one."""
    fields = set(model.field_names())
    # The grid models' kernels read rain weights only when built with a scenario mask.
    masked = 'rain_mask = ""' not in model.parameters_toml()
    takes_rain = model.rain_rate > 0 and (model.name == "sph" or masked)
    return [v for v in VARIABLES if (takes_rain if v.field == _RAIN else v.field in fields)]
