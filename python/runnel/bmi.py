# SPDX-License-Identifier: MIT
"""runnel behind the CSDMS Basic Model Interface 2.0 (bmipy), for pymt, Landlab and other couplers.

    from runnel.bmi import RunnelBmi
    bmi = RunnelBmi()
    bmi.initialize("scenario.toml")       # a runnel scenario (docs/parameters.md)
    bmi.update_until(60.0)
    z = bmi.get_value_ptr("land_surface__elevation")   # or Landlab's "topographic__elevation"

The grid is the terrain's uniform rectilinear grid of vertices (grid 0, rank 2, shape (ny, nx)) in
BMI's order: row 0 the southern row, rows counted northwards, the origin the south-west vertex at
its pixel centre, as Landlab's RasterModelGrid has it. Variables carry CSDMS Standard Names, with
Landlab's names as aliases, and UDUNITS units; vector fields are split into components
(runnel/_bmi_variables.py, docs/python.md). The elevation (float64, exact) can be set for every
model: the change is booked in the mass balance as an imposed source. The model runs on an OpenCL
device, so a value is a copy of the device state: get_value_ptr returns an array that update()
refreshes in place; set values with set_value.
"""
import numpy as np
from bmipy import Bmi

from . import InputError, Model
from ._bmi_variables import variables_of

_GRID = 0
_TIME_UNITS = {"s": "s", "yr": "yr", "iterations": "1"}


class RunnelBmi(Bmi):
    """A runnel model (the scenario's run.model) as a BMI 2.0 component."""

    def __init__(self):
        self._model = None
        self._variables = {}
        self._outputs = ()
        self._inputs = ()
        self._pointers = {}
        self._quantum = 0.0

    # Control ---------------------------------------------------------------------------------
    def initialize(self, config_file=None):
        """Builds the model of a scenario TOML file (None or "": the built-in defaults)."""
        self._model = Model.from_scenario(config_file or "")
        variables = variables_of(self._model)
        self._variables = {}
        for v in variables:
            self._variables[v.name] = self._variables[v.alias] = v
        self._outputs = tuple(v.name for v in variables)
        self._inputs = tuple(v.name for v in variables if v.input and self._settable(v))
        self._pointers = {}
        self._quantum = _height_quantum(self._model)

    def update(self):
        self._model.step()
        self._refresh()

    def update_until(self, time):
        if time < self._model.time:
            raise InputError(f"update_until: {time} is before the current time {self._model.time}")
        self._model.advance(time - self._model.time)
        self._refresh()

    def finalize(self):
        self._model = None
        self._variables = {}
        self._pointers = {}

    # Information -----------------------------------------------------------------------------
    def get_component_name(self):
        return f"runnel {self._model.name} ({self._model.class_name})"

    def get_input_item_count(self):
        return len(self._inputs)

    def get_output_item_count(self):
        return len(self._outputs)

    def get_input_var_names(self):
        return self._inputs

    def get_output_var_names(self):
        return self._outputs

    # Variables -------------------------------------------------------------------------------
    def get_var_grid(self, name):
        self._variable(name)
        return _GRID

    def get_var_type(self, name):
        return self._variable(name).dtype

    def get_var_units(self, name):
        return self._variable(name).units

    def get_var_itemsize(self, name):
        return np.dtype(self._variable(name).dtype).itemsize

    def get_var_nbytes(self, name):
        # From the description: asking for a size does not copy the field off the device.
        return self.get_var_itemsize(name) * self.get_grid_size(_GRID)

    def get_var_location(self, name):
        self._variable(name)
        return "node"

    # Time ------------------------------------------------------------------------------------
    def get_current_time(self):
        return float(self._model.time)

    def get_start_time(self):
        return 0.0

    def get_end_time(self):
        return float(self._model.run_length)

    def get_time_units(self):
        return _TIME_UNITS[self._model.clock]

    def get_time_step(self):
        # The model's next step: the one its stability limit chose (adaptive models), or its fixed
        # one. SPH chooses its first step when it takes it: before that, 0 (BMI: none yet known).
        return float(self._model.step_size)

    # Getters and setters ---------------------------------------------------------------------
    def get_value_ptr(self, name):
        variable = self._variable(name)
        if variable.name not in self._pointers:
            self._pointers[variable.name] = variable.read(self._model, self._quantum).copy()
        return self._pointers[variable.name]

    def get_value(self, name, dest):
        dest[:] = self._variable(name).read(self._model, self._quantum)
        return dest

    def get_value_at_indices(self, name, dest, inds):
        dest[:] = self._variable(name).read(self._model, self._quantum)[inds]
        return dest

    def set_value(self, name, src):
        variable = self._variable(name)
        if variable.name not in self._inputs:
            raise InputError(f"set_value: {name} is an output of the {self._model.name} model only")
        values = np.asarray(src).reshape(-1)
        if values.size != self.get_grid_size(_GRID):
            raise InputError(f"set_value: {values.size} values for {self.get_grid_size(_GRID)} nodes")
        variable.write(self._model, values)
        self._refresh()

    def set_value_at_indices(self, name, inds, src):
        values = self._variable(name).read(self._model, self._quantum).copy()
        values[inds] = src
        self.set_value(name, values)

    # Grid (uniform rectilinear) ----------------------------------------------------------------
    def get_grid_rank(self, grid):
        self._check_grid(grid)
        return 2

    def get_grid_size(self, grid):
        self._check_grid(grid)
        t = self._model.initial_terrain()
        return t.nx * t.ny

    def get_grid_type(self, grid):
        self._check_grid(grid)
        return "uniform_rectilinear"

    def get_grid_shape(self, grid, shape):
        self._check_grid(grid)
        t = self._model.initial_terrain()
        shape[:] = (t.ny, t.nx)
        return shape

    def get_grid_spacing(self, grid, spacing):
        self._check_grid(grid)
        cell = self._model.initial_terrain().cell
        spacing[:] = (cell, cell)
        return spacing

    def get_grid_origin(self, grid, origin):
        # The first node in (row, column) order, rows counted northwards: the south-west vertex,
        # at its pixel's centre, half a cell inside the raster's lower-left corner.
        self._check_grid(grid)
        t = self._model.initial_terrain()
        origin[:] = (t.origin_z + 0.5 * t.cell, t.origin_x + 0.5 * t.cell)
        return origin

    def get_grid_x(self, grid, x):
        raise NotImplementedError("get_grid_x: a uniform rectilinear grid (get_grid_spacing)")

    def get_grid_y(self, grid, y):
        raise NotImplementedError("get_grid_y: a uniform rectilinear grid (get_grid_spacing)")

    def get_grid_z(self, grid, z):
        raise NotImplementedError("get_grid_z: a uniform rectilinear grid (get_grid_spacing)")

    def get_grid_node_count(self, grid):
        return self.get_grid_size(grid)

    def get_grid_edge_count(self, grid):
        raise NotImplementedError("get_grid_edge_count: not an unstructured grid")

    def get_grid_face_count(self, grid):
        raise NotImplementedError("get_grid_face_count: not an unstructured grid")

    def get_grid_edge_nodes(self, grid, edge_nodes):
        raise NotImplementedError("get_grid_edge_nodes: not an unstructured grid")

    def get_grid_face_edges(self, grid, face_edges):
        raise NotImplementedError("get_grid_face_edges: not an unstructured grid")

    def get_grid_face_nodes(self, grid, face_nodes):
        raise NotImplementedError("get_grid_face_nodes: not an unstructured grid")

    def get_grid_nodes_per_face(self, grid, nodes_per_face):
        raise NotImplementedError("get_grid_nodes_per_face: not an unstructured grid")

    # Beyond BMI ------------------------------------------------------------------------------
    @property
    def model(self):
        """The runnel.Model behind the component (its mass balance, checkpoints, fields)."""
        return self._model

    # Helpers ---------------------------------------------------------------------------------
    def _settable(self, variable):
        # SPH's water is particles: its depth is no field to set.
        return not (variable.field == "surface_water__depth" and self._model.name == "sph")

    def _variable(self, name):
        if self._model is None:
            raise InputError("the BMI component is not initialised (call initialize first)")
        if name not in self._variables:
            raise InputError(f"{name}: not a variable of the {self._model.name} model "
                             f"({', '.join(self._outputs)})")
        return self._variables[name]

    def _check_grid(self, grid):
        if grid != _GRID:
            raise InputError(f"grid {grid}: runnel has one grid, 0")

    def _refresh(self):
        for name, array in self._pointers.items():
            array[:] = self._variables[name].read(self._model, self._quantum)


def _height_quantum(model):
    """erosion.height_quantum: metres a count of the integer height fields."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python before 3.11: the same parser from PyPI
        import tomli as tomllib

    return float(tomllib.loads(model.parameters_toml())["erosion"]["height_quantum"])
