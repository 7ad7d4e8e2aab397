// SPDX-License-Identifier: MIT
// runnel.Model: an erosion model on a terrain, stepped from Python (docs/python.md). Fields come from
// the device, so each is copied once, into an array NumPy owns.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "bindings_common.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::python {
namespace {

// A model and the context it runs on (which must outlive it).
struct PyModel {
  std::shared_ptr<ComputeContext> compute;
  std::unique_ptr<Model> model;

  Model& get() { return *model; }
};

py::dict balance_dict(const MassBalance& m) {
  py::dict d;
  d["terrain_change"] = m.terrain_change;
  d["suspended"] = m.suspended;
  d["outflow"] = m.outflow;
  d["lost"] = m.lost;
  d["uplift"] = m.uplift;
  d["imposed"] = m.imposed;
  d["residual"] = m.residual;
  d["eroded"] = m.eroded;
  d["deposited"] = m.deposited;
  d["relative"] = m.relative;
  d["residual_quanta"] = m.residual_quanta;
  return d;
}

py::object json_value(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

py::object particle_field(const HostParticles& p, const std::string& name) {
  const auto n = static_cast<py::ssize_t>(p.size());
  const auto triple = [&](ParticleField a) {
    std::vector<float> v(3 * p.size());
    for (std::size_t k = 0; k < p.size(); ++k)
      for (int c = 0; c < 3; ++c) v[3 * k + c] = p.f[a + c][k];
    return owned_array(std::move(v), {n, 3});
  };
  if (name == "particle__position") return triple(kX);
  if (name == "particle__velocity") return triple(kVx);
  if (name == "particle__density") return owned_array(p.f[kRho], {n});
  if (name == "particle__age") return owned_array(p.f[kAge], {n});
  if (name == "particle__lifespan") return owned_array(p.f[kLifespan], {n});
  if (name == "particle__sediment") return owned_array(p.sediment, {n});
  if (name == "particle__contacts") return owned_array(p.contacts, {n});
  if (name == "particle__id") return owned_array(p.id, {n});
  return py::none();
}

// A field of the model as it is now, by its dictionary name (docs/fields.md).
py::array model_field(PyModel& self, const std::string& name) {
  Model& m = self.get();
  if (name == kTopographicElevation) {
    const Heightmap t = m.terrain();
    return owned_array(t.h, grid_shape(t.ny, t.nx, 1));
  }
  const Heightmap& t = m.initial_terrain();  // the grid's shape, without a download
  const CheckpointData d = m.checkpoint();
  for (const StoredField& f : d.fields) {
    if (f.name != name) continue;
    if (!f.i64.empty()) return owned_array(f.i64, grid_shape(t.ny, t.nx, f.components));
    return owned_array(f.f32, grid_shape(t.ny, t.nx, f.components));
  }
  if (d.model == "sph") {
    py::object particles = particle_field(d.particles, name);
    if (!particles.is_none()) return particles;
  }
  throw input_error("field " + name + ": the " + m.info().name +
                    " model has no such field (see model.field_names())");
}

std::vector<std::string> field_names(PyModel& self) {
  std::vector<std::string> names = {kTopographicElevation};
  for (const FieldUse& f : self.get().info().fields)
    if (f.name != kTopographicElevation) names.push_back(f.name);
  return names;
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Replaces a float field of a grid model (BMI set_value): through the checkpoint, so the model's
// own restore validates it.
void set_model_field(PyModel& self, const std::string& name, const FloatArray& values) {
  Model& m = self.get();
  CheckpointData d = m.checkpoint();
  for (StoredField& f : d.fields) {
    if (f.name != name) continue;
    if (f.f32.empty()) throw input_error("field " + name + ": integer counts cannot be set");
    if (static_cast<std::size_t>(values.size()) != f.f32.size()) {
      throw input_error("field " + name + ": " + std::to_string(values.size()) + " values for " +
                        std::to_string(f.f32.size()));
    }
    for (py::ssize_t k = 0; k < values.size(); ++k)
      if (const std::string why = field_value_problem(name, values.data()[k]); !why.empty())
        throw input_error("field " + name + ": value " + format_number(values.data()[k]) +
                          " at index " + std::to_string(k) + " is " + why);
    std::copy(values.data(), values.data() + values.size(), f.f32.begin());
    m.restore(d);
    return;
  }
  throw input_error("field " + name + ": not a settable field of the " + m.info().name + " model");
}

// A duration in the model's clock units (s, iterations or years): finite, at least zero, and at
// most run.steps' bound of 1e12, beyond which advance() would run for ever instead of failing.
double checked_duration(const char* what, double value) {
  if (!(std::isfinite(value) && value >= 0 && value <= 1e12))
    throw input_error(std::string(what) + ": " + format_number(value) +
                      " is not a duration from 0 to 1e12 (the model's clock units)");
  return value;
}

// Advances by dt; after every step, Ctrl-C (a pending KeyboardInterrupt) stops it there, between two
// whole steps, so the model stays consistent and can go on; `progress(elapsed, dt)` is told how far
// it is.
void advance(PyModel& self, double dt, const std::optional<py::function>& progress) {
  Model& model = self.get();
  checked_duration("dt", dt);
  const double start = model.time();
  model.advance(dt, [&] {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (progress) (*progress)(std::min(model.time() - start, dt), dt);
  });
}

// The scenario's run length in the model's clock (what run() runs to, BMI's end time).
double run_length(Model& model) {
  const RunOptions o = run_options_from(model.parameters(), model.info().clock);
  if (o.until_step > 0) {
    if (model.info().clock == ModelClock::kIterations) return static_cast<double>(o.until_step);
    return static_cast<double>(o.until_step) * model.step_size();
  }
  return o.until_time;
}

constexpr const char* kModelDoc = R"doc(An erosion model on a terrain.

Parameters
----------
name : str
    The model (runnel.model_names(): "sph", "pipe", "droplet", "olsen", "thermal", "stream-power").
terrain : Terrain
    The terrain it erodes.
params : dict, optional
    Parameter keys and values (docs/parameters.md), as ``runnel run --set`` takes them.
device : str, optional
    The OpenCL device ("" the first; ``runnel devices`` lists them).

Raises
------
InputError
    A bad parameter, with the CLI's one-line message.
)doc";

}  // namespace

void bind_model(py::module_& m) {
  py::class_<PyModel>(m, "Model", kModelDoc)
      .def(py::init([](const std::string& name, const Heightmap& terrain, const py::dict& params,
                       const std::string& device) {
             Parameters p = default_parameters();
             p.set("run.model", name, "model");
             set_parameters(p, params, "params");
             // The model is the one named: params cannot name another.
             if (p.text("run.model") != name)
               throw input_error("params['run.model'] = " + runnel::quoted(p.text("run.model")) +
                                 ": the model is " + runnel::quoted(name) + ", Model's first argument");
             auto compute = context_for(device);
             return PyModel{compute, make_model(*compute, p, terrain)};
           }),
           py::arg("name"), py::arg("terrain"), py::arg("params") = py::dict(),
           py::arg("device") = "")
      .def_static(
          "from_scenario",
          [](const std::string& path, const py::dict& overrides, const std::string& device) {
            Parameters p = path.empty() ? default_parameters() : load_scenario(path);
            set_parameters(p, overrides, "overrides");
            const Heightmap terrain = load_terrain(p);
            auto compute = context_for(device);
            return PyModel{compute, make_model(*compute, p, terrain)};
          },
          py::arg("path"), py::arg("overrides") = py::dict(), py::arg("device") = "",
          R"doc(The model, terrain and parameters of a scenario file, as ``runnel run`` reads it.

Parameters
----------
path : str
    A scenario TOML file ("" for the built-in defaults).
overrides : dict, optional
    Parameter keys and values that replace the file's.
device : str, optional
    The OpenCL device.

Returns
-------
Model
)doc")
      .def_static(
          "load_checkpoint",
          [](const std::string& path, const std::string& device) {
            auto compute = context_for(device);
            return PyModel{compute,
                           make_model_from_checkpoint(*compute, read_checkpoint(path), path)};
          },
          py::arg("path"), py::arg("device") = "",
          R"doc(The model an HDF5 checkpoint holds, ready to go on exactly as it would have.

Parameters
----------
path : str
    A checkpoint (``runnel run``'s final.h5 or checkpoints/*.h5, or save_checkpoint's file).
device : str, optional
    The OpenCL device.
)doc")
      .def(
          "save_checkpoint",
          [](PyModel& self, const std::string& path) {
            write_checkpoint(path, self.get().checkpoint());
          },
          py::arg("path"),
          R"doc(Writes the whole state to an HDF5 checkpoint (docs/hdf5-schema.md), atomically.

Parameters
----------
path : str
    The file to write.
)doc")
      .def(
          "step", [](PyModel& self) { return self.get().step(); },
          R"doc(Takes one step of the model's own size.

Returns
-------
float
    The step's length, in the model's clock units (``clock``).
)doc")
      .def("advance", &advance, py::arg("dt"), py::arg("progress") = py::none(),
           R"doc(Advances the clock by dt.

Seconds models land on time + dt exactly (an adaptive step is shortened); iteration models take
round(dt) steps. Ctrl-C stops it between two steps (KeyboardInterrupt), the model left consistent
to go on.

Parameters
----------
dt : float
    The duration, in the model's clock units (``clock``: s, yr or iterations), 0 to 1e12.
progress : callable, optional
    Called after every step as ``progress(elapsed, dt)``, e.g. to move a tqdm bar.
)doc")
      .def(
          "run",
          [](PyModel& self, const std::string& out, bool quiet) {
            Model& model = self.get();
            RunOptions o = run_options_from(model.parameters(), model.info().clock);
            o.out_dir = out;
            o.quiet = quiet;
            const RunSummary s = run_model(*self.compute, model, o);
            return json_value(s.metrics.str());
          },
          py::arg("out"), py::arg("quiet") = true,
          R"doc(Runs to the scenario's length and writes what ``runnel run`` writes.

Parameters
----------
out : str
    The output folder (created).
quiet : bool, optional
    No progress on stderr (default).

Returns
-------
dict
    metrics.json's contents: mass balance, terrain metrics, timings.
)doc")
      .def_property_readonly(
          "name", [](PyModel& self) { return self.get().info().name; }, "The model's registry key.")
      .def_property_readonly(
          "class_name", [](PyModel& self) { return self.get().info().class_name; },
          "The class named after the model's paper (Erosion_Mei2007, ...).")
      .def_property_readonly(
          "clock", [](PyModel& self) { return std::string(clock_name(self.get().info().clock)); },
          "The clock's units: \"s\", \"yr\" (stream-power) or \"iterations\".")
      .def_property_readonly(
          "time", [](PyModel& self) { return self.get().time(); },
          "The model's time, in its clock's units.")
      .def_property_readonly(
          "step_size", [](PyModel& self) { return self.get().step_size(); },
          "The length of the next step in the clock's units: the step an adaptive model's stability "
          "limit chose after its latest step (SPH: 0 before its first), or its fixed one.")
      .def_property_readonly(
          "run_length", [](PyModel& self) { return run_length(self.get()); },
          "The scenario's run length in the clock's units (run.sim_time, run.sim_years, "
          "run.iterations or run.steps): what run() runs to.")
      .def_property_readonly(
          "steps", [](PyModel& self) { return self.get().steps(); }, "Steps taken so far.")
      .def(
          "terrain", [](PyModel& self) { return self.get().terrain(); },
          "The terrain as it is now (a copy, float32 heights).")
      .def(
          "initial_terrain", [](PyModel& self) { return self.get().initial_terrain(); },
          "The terrain the model started from.")
      .def(
          "elevation",
          [](PyModel& self) {
            const Heightmap& t = self.get().initial_terrain();
            return owned_array(self.get().elevation(), grid_shape(t.ny, t.nx, 1));
          },
          R"doc(The terrain's exact heights, in metres.

Returns
-------
numpy.ndarray
    float64, shape (ny, nx), row 0 the northern row: each height is an exact count of the height
    quantum, so set_elevation(elevation()) changes nothing.
)doc")
      .def(
          "set_elevation",
          [](PyModel& self, const DoubleArray& heights) {
            const double* data = heights.data();
            self.get().set_elevation(std::vector<double>(data, data + heights.size()));
          },
          py::arg("heights"),
          R"doc(Replaces the terrain's heights (a coupler's uplift or hillslope change).

The change is rounded to the height quantum and booked in the mass balance as an imposed external
source (``mass_balance()["imposed"]``), never as erosion or deposition. Refused with a layer
stack (ground.layers).

Parameters
----------
heights : array_like
    ny x nx heights in metres, row 0 the northern row (as elevation() gives them).
)doc")
      .def_property_readonly(
          "rain_rate", [](PyModel& self) { return self.get().rain_rate(); },
          "The scenario's rain as a rate over the whole terrain, m/s (0: the model takes no rain "
          "field).")
      .def(
          "set_rain_rates",
          [](PyModel& self, const FloatArray& rates) {
            const float* data = rates.data();
            self.get().set_rain_rates(std::vector<float>(data, data + rates.size()));
          },
          py::arg("rates"),
          R"doc(Rains a rate at every vertex in place of the scenario's rain.

Kept as the rain mask's weights against rain_rate, so the scenario needs rain; the pipe model also
needs a rain mask (ground.rain_mask), whose kernels read the weights. SPH takes one on any
scenario with rain.

Parameters
----------
rates : array_like
    ny x nx rain rates, m/s, at least 0, row 0 the northern row.
)doc")
      .def(
          "mass_balance", [](PyModel& self) { return balance_dict(self.get().mass_balance()); },
          R"doc(The mass balance, in m³ (docs/models.md, "Metrics").

Returns
-------
dict
    terrain_change, suspended, outflow, lost, uplift, imposed, residual (0 on a conserving run),
    residual_quanta, eroded, deposited, relative.
)doc")
      .def(
          "diagnostics", [](PyModel& self) { return json_value(self.get().diagnostics().str()); },
          "The model's own metrics.json entries (counters, effective settings), as a dict.")
      .def("__repr__",
           [](PyModel& self) {
             Model& model = self.get();
             std::ostringstream s;
             s << "<runnel.Model " << model.info().name << " (" << model.info().class_name
               << "), " << model.steps() << " steps, t = " << model.time()
               << clock_suffix(model.info().clock) << ">";
             return s.str();
           })
      .def(
          "parameters_toml",
          [](PyModel& self) { return parameters_toml(self.get().parameters()); },
          "The full parameter set, as a scenario TOML text.")
      .def("field", &model_field, py::arg("name"),
           R"doc(A field of the model as it is now (a copy).

Parameters
----------
name : str
    A name of field_names() (docs/fields.md).

Returns
-------
numpy.ndarray
    Vertex fields (ny, nx) or (ny, nx, components), row 0 the northern row; particle fields (n,)
    or (n, 3).
)doc")
      .def("set_field", &set_model_field, py::arg("name"), py::arg("values"),
           R"doc(Replaces a float vertex field of a grid model (e.g. surface_water__depth).

Parameters
----------
name : str
    The field.
values : array_like
    Its new values, as many as field(name) has.
)doc")
      .def("field_names", &field_names, "The names of the model's fields (docs/fields.md).")
      .def(
          "field_info",
          [](PyModel&, const std::string& name) {
            const FieldDescription& d = field_description(name);
            py::dict info;
            info["location"] = to_string(d.location);
            info["type"] = to_string(d.type);
            info["components"] = d.components;
            info["unit"] = d.unit;
            info["doc"] = d.doc;
            return info;
          },
          py::arg("name"),
          R"doc(A field's description (docs/fields.md).

Parameters
----------
name : str
    A field of the dictionary.

Returns
-------
dict
    location, type, components, unit and doc.
)doc");
}

}  // namespace runnel::python
