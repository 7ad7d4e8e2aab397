// SPDX-License-Identifier: MIT
// runnel._runnel: the thin pybind11 layer over the C++ core (docs/python.md). Terrains share their
// heights with NumPy without a copy; the models are in bindings_model.cpp. runnel::Error becomes
// runnel.InputError (bad input, a ValueError) or runnel.RunnelRuntimeError (a failure while
// running, a RuntimeError), with the CLI's message.
#include <pybind11/stl.h>

#include <cmath>

#include <map>
#include <sstream>

#include "bindings_common.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/core/version.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/netcdf_io.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel::python {

// The table is never destroyed: a context released at the interpreter's exit, after the OpenCL
// implementation's own statics, can crash it.
std::shared_ptr<ComputeContext> context_for(const std::string& device) {
  static auto& contexts = *new std::map<std::string, std::shared_ptr<ComputeContext>>;
  auto& slot = contexts[device];
  if (!slot) slot = std::make_shared<ComputeContext>(device);
  return slot;
}

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

namespace {

// Heights as float32 from an array of real numbers: a complex, boolean, text or object array is
// refused rather than cast (NumPy would drop a complex number's imaginary part).
py::array_t<float, py::array::c_style | py::array::forcecast> real_heights(const py::array& heights) {
  const char kind = heights.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw input_error("heights: an array of real numbers is needed (got dtype " +
                      std::string(py::str(heights.dtype())) + ")");
  return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(heights);
}

// A terrain of `cell` m holding the heights of a 2-D array of real numbers, unchecked beyond its
// shape (the callers check the values once they are what the terrain will hold).
Heightmap terrain_of_array(const py::array& array, double cell) {
  const auto heights = real_heights(array);
  if (heights.ndim() != 2) throw input_error("heights: a 2-D array (rows, columns) is needed");
  check_terrain_size("heights", heights.shape(1), heights.shape(0));
  Heightmap t(static_cast<int>(heights.shape(1)), static_cast<int>(heights.shape(0)), cell);
  std::copy(heights.data(), heights.data() + heights.size(), t.h.begin());
  // Double precision kept as given: a model then starts from these heights, exact to the quantum.
  if (array.dtype().is(py::dtype::of<double>())) {
    const auto exact = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    t.exact.assign(exact.data(), exact.data() + exact.size());
  }
  return t;
}

Heightmap terrain_from(const py::array& array, double cell) {
  Heightmap t = terrain_of_array(array, cell);
  check_terrain_values("heights", t);
  return t;
}

// A terrain whose `holes` (true: NODATA) are filled from their neighbours and kept as holes, written
// back as `nodata` (terrain_from_landlab's closed nodes).
Heightmap terrain_with_holes(const py::array& array, double cell,
                             const py::array_t<bool, py::array::c_style | py::array::forcecast>& holes,
                             double nodata) {
  Heightmap t = terrain_of_array(array, cell);
  if (holes.ndim() != 2 || holes.shape(0) != t.ny || holes.shape(1) != t.nx)
    throw input_error("holes: a 2-D array of the heights' shape is needed");
  long long count = 0;
  for (std::size_t k = 0; k < t.h.size(); ++k)
    if (holes.data()[k]) {
      t.h[k] = NAN;  // what apply_nodata_policy fills and marks
      ++count;
    }
  t.georef.nodata = nodata;
  apply_nodata_policy("heights", t, count, NodataPolicy::kFill);
  check_terrain_values("heights", t);
  return t;
}

py::dict terrain_metrics(const Heightmap& initial, const Heightmap& final_terrain) {
  if (initial.nx != final_terrain.nx || initial.ny != final_terrain.ny ||
      initial.cell != final_terrain.cell)
    throw input_error("final: " + std::to_string(final_terrain.nx) + " x " +
                      std::to_string(final_terrain.ny) + " vertices of " +
                      format_number(final_terrain.cell) + " m, not the initial terrain's " +
                      std::to_string(initial.nx) + " x " + std::to_string(initial.ny) + " of " +
                      format_number(initial.cell) + " m");
  py::dict d;
  const auto area = metrics::flow_accumulation(final_terrain);
  for (const auto& [k, v] : metrics::terrain_metric_values(initial, final_terrain, area))
    d[py::str(k)] = v;
  return d;
}

constexpr const char* kTerrainDoc = R"doc(A heightmap: heights in metres on nx x ny vertices, cell metres apart.

Row 0 is the northern row. The vertices sit at the centres of the raster's pixels: vertex (row j,
column i) is at map x = origin_x + (i + 0.5)·cell, y = origin_z + (ny − j − 0.5)·cell, where
(origin_x, origin_z) is the raster's lower-left corner (docs/terrain-formats.md).

Parameters
----------
heights : array_like
    A 2-D array (rows, columns) of finite heights in metres.
cell : float, optional
    The spacing of the vertices, m (default 1).
)doc";

}  // namespace

void bind_terrain(py::module_& m) {
  py::class_<Heightmap>(m, "Terrain", kTerrainDoc)
      .def(py::init(&terrain_from), py::arg("heights"), py::arg("cell") = 1.0)
      .def_readonly("nx", &Heightmap::nx, "Vertices west to east.")
      .def_readonly("ny", &Heightmap::ny, "Vertices north to south.")
      .def_property(
          "cell", [](const Heightmap& t) { return t.cell; },
          [](Heightmap& t, double cell) {
            check_cell_size("cell", cell);
            t.cell = cell;
          },
          "The vertex spacing, m.")
      .def_property(
          "origin_x", [](const Heightmap& t) { return t.origin_x; },
          [](Heightmap& t, double x) {
            check_origin("origin_x", x, 0.0);
            t.origin_x = x;
          },
          "Map x of the raster's western edge, m (a pixel corner, half a cell west of column 0).")
      .def_property(
          "origin_z", [](const Heightmap& t) { return t.origin_z; },
          [](Heightmap& t, double z) {
            check_origin("origin_z", 0.0, z);
            t.origin_z = z;
          },
          "Map y of the raster's southern edge, m (half a cell south of the last row).")
      .def_property(
          "crs_wkt", [](const Heightmap& t) { return t.georef.crs_wkt; },
          [](Heightmap& t, const std::string& wkt) { t.georef.crs_wkt = wkt; },
          "The coordinate reference system as OGC WKT (\"\": not georeferenced).")
      .def_property_readonly(
          "nodata", [](const Heightmap& t) { return t.georef.nodata; },
          "The source raster's NODATA value, or None.")
      .def_property_readonly(
          "holes",
          [](const Heightmap& t) {
            py::array_t<bool> holes({t.ny, t.nx});
            bool* out = holes.mutable_data();
            for (std::size_t k = 0; k < t.size(); ++k) out[k] = t.georef.hole(k);
            return holes;
          },
          "Where the source had NODATA, (ny, nx) bool (a copy; all False without holes): filled "
          "from their neighbours to run, written back as NODATA.")
      // The heights without a copy: the array looks into the terrain's own memory.
      .def_property_readonly(
          "heights",
          [](py::object self) {
            Heightmap& t = self.cast<Heightmap&>();
            return py::array_t<float>({t.ny, t.nx}, t.h.data(), self);
          },
          "The heights, (ny, nx) float32, m: a view, not a copy.")
      .def("volume", &Heightmap::volume, "The volume above height 0: cell² times the heights' sum, m³.")
      .def("__repr__", [](const Heightmap& t) {
        std::ostringstream s;
        s << "<runnel.Terrain " << t.nx << " x " << t.ny << ", cell " << t.cell << " m, CRS "
          << crs_name(t.georef.crs_wkt) << ">";
        return s.str();
      });

  m.def("_terrain_with_holes", &terrain_with_holes, py::arg("heights"), py::arg("cell"),
        py::arg("holes"), py::arg("nodata"),
        "A Terrain whose holes (True: NODATA) are filled from their neighbours and kept as holes.");
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
      R"doc(Reads a terrain file with its georeferencing.

Parameters
----------
path : str
    .asc, .png, .npy, .tif or another raster GDAL reads (docs/terrain-formats.md).
nodata : {"fill", "refuse"}, optional
    NODATA holes filled from their neighbours (default), or refused.
cell : float, optional
    The vertex spacing, m, for formats that do not carry one (.png, .npy).

Returns
-------
Terrain
)doc");
  m.def(
      "write_terrain",
      [](const std::string& path, const Heightmap& t) {
        check_terrain_values("terrain", t);  // heights edited through the view: as readers take them
        write_terrain(path, t);
      },
      py::arg("path"), py::arg("terrain"),
      R"doc(Writes a terrain, the format from the extension (.asc, .png, .npy or .tif).

Parameters
----------
path : str
    The file (written atomically).
terrain : Terrain
)doc");
  m.def(
      "generate",
      [](const std::string& name, int nx, int ny, double cell, std::uint64_t seed,
         const std::map<std::string, double>& params) {
        return generate_terrain(name, nx, ny, cell, seed, params);
      },
      py::arg("name"), py::arg("nx") = 129, py::arg("ny") = 129, py::arg("cell") = 1.0,
      py::arg("seed") = 1, py::arg("params") = std::map<std::string, double>{},
      R"doc(A generated terrain, seeded and deterministic.

Parameters
----------
name : str
    A generator of generator_names() (``runnel generate --help`` describes them).
nx, ny : int, optional
    Vertices west to east and north to south (default 129).
cell : float, optional
    The vertex spacing, m (default 1).
seed : int, optional
params : dict, optional
    The generator's parameters (relief, octaves, ...).

Returns
-------
Terrain
)doc");
  m.def(
      "generator_names",
      [] {
        std::vector<std::string> names;
        for (const auto& g : generators()) names.push_back(g.name);
        return names;
      },
      "The terrain generators' names.");
  m.def("model_names", &model_names, "The erosion models' names (runnel.Model's first argument).");
  m.def(
      "_cf_grid_mapping",
      [](const std::string& crs_wkt) {
        py::dict attributes;
        for (const CfAttribute& a : cf_grid_mapping(crs_wkt)) {
          if (a.is_number) {
            attributes[py::str(a.name)] = a.number;
          } else {
            attributes[py::str(a.name)] = a.text;
          }
        }
        return attributes;
      },
      py::arg("crs_wkt"),
      "The CF grid mapping attributes of a CRS, as runnel's NetCDF export writes them.");
  m.def(
      "_cf_time_attributes",
      [](const std::string& units) {
        py::dict attributes;
        for (const auto& [name, value] : cf_time_attributes(units)) attributes[py::str(name)] = value;
        return attributes;
      },
      py::arg("units"),
      "The CF attributes of the time coordinate for a model clock's units (s, yr or 1).");
  m.def("terrain_metrics", &terrain_metrics, py::arg("initial"), py::arg("final"),
        R"doc(The shared terrain metrics of docs/metrics.md between two states of one terrain.

Parameters
----------
initial, final : Terrain
    The same grid before and after.

Returns
-------
dict
    Metric name to value.
)doc");
}

}  // namespace runnel::python

PYBIND11_MODULE(_runnel, m) {
  namespace py = pybind11;
  using namespace runnel;
  m.doc() = "runnel's C++ core (use the runnel package, not this module)";
  m.attr("__version__") = kVersion;

  static py::exception<Error> input_exception(m, "InputError", PyExc_ValueError);
  static py::exception<Error> runtime_exception(m, "RunnelRuntimeError", PyExc_RuntimeError);
  input_exception.doc() = "Bad input (a ValueError), with the CLI's one-line message.";
  runtime_exception.doc() = "A failure while running (a RuntimeError), with the CLI's message.";
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
  python::bind_terrain(m);
  python::bind_model(m);
}
