# SPDX-License-Identifier: MIT
"""runnel behind the CSDMS Basic Model Interface 2.0 (bmipy), for pymt, Landlab and other couplers.

    from runnel.bmi import RunnelBmi
    bmi = RunnelBmi()
    bmi.initialize("scenario.toml")       # a runnel scenario (docs/parameters.md)
    bmi.update_until(60.0)
    z = bmi.get_value_ptr("topographic__elevation")

The grid is the terrain's uniform rectilinear grid of vertices (grid 0, rank 2, shape (ny, nx),
row 0 the northern row, as in the terrain files). Variables are the model's vertex fields from the
field dictionary (docs/fields.md). topographic__elevation is given in metres (the model keeps it as
exact integer counts of erosion.height_quantum). The model runs on an OpenCL device, so a value is a
copy of the device state: get_value_ptr returns an array that update() refreshes in place.
"""
import numpy as np
from bmipy import Bmi

from . import InputError, Model

_GRID = 0


class RunnelBmi(Bmi):
    """A runnel model (the scenario's run.model) as a BMI 2.0 component."""

    def __init__(self):
        self._model = None
        self._end_time = 0.0
        self._pointers = {}

    # Control ---------------------------------------------------------------------------------
    def initialize(self, config_file=None):
        """Builds the model of a scenario TOML file (None or "": the built-in defaults)."""
        self._model = Model.from_scenario(config_file or "")
        self._end_time = _run_length(self._model)
        self._pointers = {}

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
        self._pointers = {}

    # Information -----------------------------------------------------------------------------
    def get_component_name(self):
        return f"runnel {self._model.name} ({self._model.class_name})"

    def get_input_item_count(self):
        return len(self.get_input_var_names())

    def get_output_item_count(self):
        return len(self.get_output_var_names())

    def get_input_var_names(self):
        # What a coupler may set: the terrain's heights (in the model: after a restart) and the
        # float fields a grid model keeps (water depth ...). Read-only counts are outputs only.
        return tuple(name for name in self._vertex_fields() if self._settable(name))

    def get_output_var_names(self):
        return tuple(self._vertex_fields())

    # Variables -------------------------------------------------------------------------------
    def get_var_grid(self, name):
        self._check(name)
        return _GRID

    def get_var_type(self, name):
        return str(self._dtype(name))

    def get_var_units(self, name):
        self._check(name)
        if name == "topographic__elevation":
            return "m"
        return self._model.field_info(name)["unit"]

    def get_var_itemsize(self, name):
        return self._dtype(name).itemsize

    def get_var_nbytes(self, name):
        # From the field's description: asking for a type or a size does not copy the field off the device.
        components = 1 if name == "topographic__elevation" else self._model.field_info(name)["components"]
        return self._dtype(name).itemsize * components * self.get_grid_size(_GRID)

    def get_var_location(self, name):
        self._check(name)
        return "node"

    # Time ------------------------------------------------------------------------------------
    def get_current_time(self):
        return float(self._model.time)

    def get_start_time(self):
        return 0.0

    def get_end_time(self):
        return float(self._end_time)

    def get_time_units(self):
        return "s" if self._model.clock == "s" else "1"

    def get_time_step(self):
        # The model's next step: the one its stability limit chose (adaptive models), or its fixed
        # one. SPH chooses its first step when it takes it: before that, 1.
        step = float(self._model.step_size)
        return step if step > 0 else 1.0

    # Getters and setters ---------------------------------------------------------------------
    def get_value_ptr(self, name):
        self._check(name)
        if name not in self._pointers:
            self._pointers[name] = self._value(name).reshape(-1).copy()
        return self._pointers[name]

    def get_value(self, name, dest):
        dest[:] = self._value(name).reshape(-1)
        return dest

    def get_value_at_indices(self, name, dest, inds):
        dest[:] = self._value(name).reshape(-1)[inds]
        return dest

    def set_value(self, name, src):
        self._check(name)
        if not self._settable(name):
            raise InputError(f"set_value: {name} is an output of the {self._model.name} model only")
        values = np.asarray(src, dtype=np.float32).reshape(-1)
        self._model.set_field(name, values)
        self._refresh()

    def set_value_at_indices(self, name, inds, src):
        values = self._value(name).reshape(-1).astype(np.float32)
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
        # BMI's origin is the first node in (row, column) order: the north-west vertex, at
        # (origin_z + (ny - 1)·cell, origin_x) in the terrain file's coordinates. Rows count south.
        self._check_grid(grid)
        t = self._model.initial_terrain()
        origin[:] = (t.origin_z + (t.ny - 1) * t.cell, t.origin_x)
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

    # Helpers ---------------------------------------------------------------------------------
    def _vertex_fields(self):
        names = []
        for name in self._model.field_names():
            if name == "topographic__elevation" or self._model.field_info(name)["location"] == "vertex":
                names.append(name)
        return names

    def _settable(self, name):
        if name == "topographic__elevation":
            return False  # exact integer state; a new terrain is a new model
        return self._model.field_info(name)["type"] == "float32"

    def _check(self, name):
        if self._model is None:
            raise InputError("the BMI component is not initialised (call initialize first)")
        if name not in self._vertex_fields():
            raise InputError(f"{name}: not a variable of the {self._model.name} model "
                             f"({', '.join(self._vertex_fields())})")

    def _check_grid(self, grid):
        if grid != _GRID:
            raise InputError(f"grid {grid}: runnel has one grid, 0")

    def _dtype(self, name):
        self._check(name)
        if name == "topographic__elevation":
            return np.dtype(np.float32)  # metres, the float view of the exact integer state
        return np.dtype(self._model.field_info(name)["type"])

    def _value(self, name):
        self._check(name)
        return self._model.field(name)

    def _refresh(self):
        for name, array in self._pointers.items():
            array[:] = self._value(name).reshape(-1)


def _run_length(model):
    """The scenario's run length in the model's clock: run.sim_time or run.iterations (or
    run.steps, at the model's current step size)."""
    import tomllib

    run = tomllib.loads(model.parameters_toml()).get("run", {})
    if model.clock == "s" and run.get("sim_time", 0) > 0:
        return float(run["sim_time"])
    if model.clock != "s" and run.get("iterations", 0) > 0:
        return float(run["iterations"])
    return float(run.get("steps", 0))
