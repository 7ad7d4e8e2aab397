// SPDX-License-Identifier: MIT
// runnel._runnel: the thin pybind11 layer over the C++ core (docs/python.md). Terrains share their
// heights with NumPy without a copy; model fields come from the device, so they are copied once,
// into arrays NumPy owns. runnel::Error becomes runnel.InputError (bad input, a ValueError) or
// runnel.RunnelRuntimeError (a failure while running, a RuntimeError), with the CLI's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <sstream>

#include "runnel/compare/compare.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/core/version.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace py = pybind11;
using namespace runnel;

namespace {

// One OpenCL context per device, shared by every model on it (building the kernels is the slow part).
// The table is never destroyed: a context released at the interpreter's exit, after the OpenCL
// implementation's own statics, can crash it.
std::shared_ptr<ComputeContext> context_for(const std::string& device) {
  static auto& contexts = *new std::map<std::string, std::shared_ptr<ComputeContext>>;
  auto& slot = contexts[device];
  if (!slot) slot = std::make_shared<ComputeContext>(device);
  return slot;
}

// Python values as parameter text: what `--set key=value` and a TOML file give.
void set_parameters(Parameters& p, const py::dict& values, const std::string& origin) {
  for (const auto& [key, value] : values) {
    const std::string k = py::str(key);
    std::string text;
    if (py::isinstance<py::bool_>(value))
      text = value.cast<bool>() ? "true" : "false";
    else
      text = py::str(value);
    p.set_text(k, text, origin);
  }
}

py::array_t<float> grid_array(std::vector<float> values, int ny, int nx, int components) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule free(owned, [](void* v) { delete static_cast<std::vector<float>*>(v); });
  std::vector<py::ssize_t> shape = {ny, nx};
  if (components > 1) shape.push_back(components);
  return py::array_t<float>(shape, owned->data(), free);
}

template <typename T>
py::array owned_array(std::vector<T> values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* v) { delete static_cast<std::vector<T>*>(v); });
  return py::array_t<T>(shape, owned->data(), free);
}

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
  d["residual"] = m.residual;
  d["eroded"] = m.eroded;
  d["deposited"] = m.deposited;
  d["relative"] = m.relative;
  d["residual_quanta"] = m.residual_quanta;
  return d;
}

// A field of the model as it is now, by its dictionary name (docs/fields.md).
py::array model_field(PyModel& self, const std::string& name) {
  Model& m = self.get();
  if (name == kTopographicElevation) {
    const Heightmap t = m.terrain();
    return grid_array(t.h, t.ny, t.nx, 1);
  }
  const Heightmap& t = m.initial_terrain();  // the grid's shape, without a download
  const CheckpointData d = m.checkpoint();
  for (const StoredField& f : d.fields) {
    if (f.name != name) continue;
    std::vector<py::ssize_t> shape = {t.ny, t.nx};
    if (f.components > 1) shape.push_back(f.components);
    if (!f.i64.empty()) return owned_array(f.i64, shape);
    return owned_array(f.f32, shape);
  }
  const HostParticles& p = d.particles;
  const auto n = static_cast<py::ssize_t>(p.size());
  const auto triple = [&](ParticleField a) {
    std::vector<float> v(3 * p.size());
    for (std::size_t k = 0; k < p.size(); ++k)
      for (int c = 0; c < 3; ++c) v[3 * k + c] = p.f[a + c][k];
    return owned_array(std::move(v), {n, 3});
  };
  if (d.model == "sph") {
    if (name == "particle__position") return triple(kX);
    if (name == "particle__velocity") return triple(kVx);
    if (name == "particle__density") return owned_array(p.f[kRho], {n});
    if (name == "particle__age") return owned_array(p.f[kAge], {n});
    if (name == "particle__lifespan") return owned_array(p.f[kLifespan], {n});
    if (name == "particle__sediment") return owned_array(p.sediment, {n});
    if (name == "particle__contacts") return owned_array(p.contacts, {n});
    if (name == "particle__id") return owned_array(p.id, {n});
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

// Replaces a float field of a grid model (BMI set_value): through the checkpoint, so the model's
// own restore validates it.
void set_model_field(PyModel& self, const std::string& name, py::array_t<float, py::array::c_style |
                                                                             py::array::forcecast>
                                                                 values) {
  Model& m = self.get();
  CheckpointData d = m.checkpoint();
  for (StoredField& f : d.fields) {
    if (f.name != name) continue;
    if (f.f32.empty()) throw input_error("field " + name + ": integer counts cannot be set");
    if (static_cast<std::size_t>(values.size()) != f.f32.size()) {
      throw input_error("field " + name + ": " + std::to_string(values.size()) + " values for " +
                        std::to_string(f.f32.size()));
    }
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

Heightmap terrain_from(py::array_t<float, py::array::c_style | py::array::forcecast> heights,
                       double cell) {
  if (heights.ndim() != 2) throw input_error("heights: a 2-D array (rows, columns) is needed");
  check_terrain_size("heights", heights.shape(1), heights.shape(0));
  Heightmap t(static_cast<int>(heights.shape(1)), static_cast<int>(heights.shape(0)), cell);
  std::copy(heights.data(), heights.data() + heights.size(), t.h.begin());
  check_terrain_values("heights", t);
  return t;
}

}  // namespace

PYBIND11_MODULE(_runnel, m) {
  m.doc() = "runnel's C++ core (use the runnel package, not this module)";
  m.attr("__version__") = kVersion;

  static py::exception<Error> input_exception(m, "InputError", PyExc_ValueError);
  static py::exception<Error> runtime_exception(m, "RunnelRuntimeError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      if (e.code() == ExitCode::kUsage)
        input_exception(e.what());
      else
        runtime_exception(e.what());
    }
  });

  py::class_<Heightmap>(m, "Terrain", "A heightmap: heights (m) on nx x ny vertices, cell metres apart")
      .def(py::init(&terrain_from), py::arg("heights"), py::arg("cell") = 1.0)
      .def_readonly("nx", &Heightmap::nx)
      .def_readonly("ny", &Heightmap::ny)
      .def_property(
          "cell", [](const Heightmap& t) { return t.cell; },
          [](Heightmap& t, double cell) {
            check_cell_size("cell", cell);
            t.cell = cell;
          })
      .def_property(
          "origin_x", [](const Heightmap& t) { return t.origin_x; },
          [](Heightmap& t, double x) {
            check_origin("origin_x", x, 0.0);
            t.origin_x = x;
          })
      .def_property(
          "origin_z", [](const Heightmap& t) { return t.origin_z; },
          [](Heightmap& t, double z) {
            check_origin("origin_z", 0.0, z);
            t.origin_z = z;
          })
      .def_property(
          "crs_wkt", [](const Heightmap& t) { return t.georef.crs_wkt; },
          [](Heightmap& t, const std::string& wkt) { t.georef.crs_wkt = wkt; })
      .def_property_readonly("nodata", [](const Heightmap& t) { return t.georef.nodata; })
      // The heights without a copy: the array looks into the terrain's own memory.
      .def_property_readonly(
          "heights",
          [](py::object self) {
            Heightmap& t = self.cast<Heightmap&>();
            return py::array_t<float>({t.ny, t.nx}, t.h.data(), self);
          })
      .def("volume", &Heightmap::volume)
      .def("__repr__", [](const Heightmap& t) {
        std::ostringstream s;
        s << "<runnel.Terrain " << t.nx << " x " << t.ny << ", cell " << t.cell << " m, CRS "
          << crs_name(t.georef.crs_wkt) << ">";
        return s.str();
      });

  m.def(
      "read_terrain",
      [](const std::string& path, const std::string& nodata, std::optional<double> cell) {
        ReadOptions o;
        if (nodata != "fill" && nodata != "refuse")
          throw input_error("nodata: '" + nodata + "' is not fill or refuse");
        o.nodata = nodata == "fill" ? NodataPolicy::kFill : NodataPolicy::kRefuse;
        o.cell = cell;
        return read_terrain(path, o);
      },
      py::arg("path"), py::arg("nodata") = "fill", py::arg("cell") = py::none(),
      "Reads .asc, .png, .npy, .tif or another raster GDAL reads (with its georeferencing)");
  m.def(
      "write_terrain", [](const std::string& path, const Heightmap& t) { write_terrain(path, t); },
      py::arg("path"), py::arg("terrain"), "Writes .asc, .png, .npy or .tif (from the extension)");
  m.def(
      "generate",
      [](const std::string& name, int nx, int ny, double cell, std::uint64_t seed,
         const std::map<std::string, double>& params) {
        return generate_terrain(name, nx, ny, cell, seed, params);
      },
      py::arg("name"), py::arg("nx") = 129, py::arg("ny") = 129, py::arg("cell") = 1.0,
      py::arg("seed") = 1, py::arg("params") = std::map<std::string, double>{},
      "A generated terrain (seeded, deterministic): runnel generate --help lists the generators");
  m.def("generator_names", [] {
    std::vector<std::string> names;
    for (const auto& g : generators()) names.push_back(g.name);
    return names;
  });
  m.def("model_names", &model_names);
  m.def(
      "terrain_metrics",
      [](const Heightmap& initial, const Heightmap& final_terrain) {
        if (initial.nx != final_terrain.nx || initial.ny != final_terrain.ny ||
            initial.cell != final_terrain.cell)
          throw input_error("final: " + std::to_string(final_terrain.nx) + " x " +
                            std::to_string(final_terrain.ny) + " vertices of " +
                            format_number(final_terrain.cell) + " m, not the initial terrain's " +
                            std::to_string(initial.nx) + " x " + std::to_string(initial.ny) +
                            " of " + format_number(initial.cell) + " m");
        py::dict d;
        const auto area = metrics::flow_accumulation(final_terrain);
        for (const auto& [k, v] : metrics::terrain_metric_values(initial, final_terrain, area))
          d[py::str(k)] = v;
        return d;
      },
      py::arg("initial"), py::arg("final"), "The shared metrics of docs/metrics.md");

  py::class_<PyModel>(m, "Model", "An erosion model on a terrain (docs/python.md)")
      .def(py::init([](const std::string& name, const Heightmap& terrain, const py::dict& params,
                       const std::string& device) {
             Parameters p = default_parameters();
             p.set("run.model", name, "model");
             set_parameters(p, params, "params");
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
          "The model, terrain and parameters of a scenario TOML file (as runnel run reads it)")
      .def_static(
          "load_checkpoint",
          [](const std::string& path, const std::string& device) {
            auto compute = context_for(device);
            return PyModel{compute, make_model_from_checkpoint(*compute, read_checkpoint(path), path)};
          },
          py::arg("path"), py::arg("device") = "", "The model a checkpoint holds, ready to go on")
      .def("save_checkpoint",
           [](PyModel& self, const std::string& path) { write_checkpoint(path, self.get().checkpoint()); })
      .def("step", [](PyModel& self) { return self.get().step(); }, "One step; returns its length")
      .def(
          "advance",
          [](PyModel& self, double dt) { self.get().advance(checked_duration("dt", dt)); },
          py::arg("dt"),
           "Advances the clock by dt (s, or iterations)")
      .def(
          "run",
          [](PyModel& self, const std::string& out, bool quiet) {
            Model& model = self.get();
            RunOptions o = run_options_from(model.parameters(), model.info().clock);
            o.out_dir = out;
            o.quiet = quiet;
            const RunSummary s = run_model(*self.compute, model, o);
            return s.metrics.str();
          },
          py::arg("out"), py::arg("quiet") = true,
          "Runs to the scenario's length and writes what runnel run writes; returns metrics.json")
      .def_property_readonly("name", [](PyModel& self) { return self.get().info().name; })
      .def_property_readonly("class_name", [](PyModel& self) { return self.get().info().class_name; })
      .def_property_readonly("clock",
                             [](PyModel& self) {
                               return self.get().info().clock == ModelClock::kSeconds ? "s" : "iterations";
                             })
      .def_property_readonly("time", [](PyModel& self) { return self.get().time(); })
      .def_property_readonly(
          "step_size", [](PyModel& self) { return self.get().step_size(); },
          "The length of the next step in the model's clock units: the step an adaptive model's "
          "stability limit chose after its latest step (SPH: 0 before its first), or its fixed one.")
      .def_property_readonly("steps", [](PyModel& self) { return self.get().steps(); })
      .def("terrain", [](PyModel& self) { return self.get().terrain(); })
      .def("initial_terrain", [](PyModel& self) { return self.get().initial_terrain(); })
      .def("mass_balance", [](PyModel& self) { return balance_dict(self.get().mass_balance()); })
      .def(
          "diagnostics",
          [](PyModel& self) {
            return py::module_::import("json").attr("loads")(self.get().diagnostics().str());
          },
          "The model's own metrics.json entries (counters, effective settings)")
      .def("__repr__",
           [](PyModel& self) {
             Model& model = self.get();
             std::ostringstream s;
             s << "<runnel.Model " << model.info().name << " (" << model.info().class_name << "), "
               << model.steps() << " steps, t = " << model.time()
               << (model.info().clock == ModelClock::kSeconds ? " s" : " iterations") << ">";
             return s.str();
           })
      .def("parameters_toml", [](PyModel& self) { return parameters_toml(self.get().parameters()); })
      .def("field", &model_field, py::arg("name"))
      .def("set_field", &set_model_field, py::arg("name"), py::arg("values"))
      .def("field_names", &field_names)
      .def("field_info", [](PyModel&, const std::string& name) {
        const FieldDescription& d = field_description(name);
        py::dict info;
        info["location"] = to_string(d.location);
        info["type"] = to_string(d.type);
        info["components"] = d.components;
        info["unit"] = d.unit;
        info["doc"] = d.doc;
        return info;
      });
}
