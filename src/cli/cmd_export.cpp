// SPDX-License-Identifier: MIT
// runnel export: the terrain of a checkpoint as ASC, PNG, NPY or an OBJ triangle mesh.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/memory_check.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/series.hpp"
#include "runnel/terrain/netcdf_io.hpp"
#include "runnel/terrain/terrain_normals.hpp"

namespace runnel::cli {
namespace {

// Wavefront OBJ: one vertex per grid point in the map frame of the series and PLY files (x east,
// y north, z up, metres, the vertices at their pixels' centres), vertex normals, and two
// triangles per tile split along (i, j)–(i+1, j+1), wound counter-clockwise seen from above.
void write_obj(const std::string& path, const Heightmap& t) {
  const std::vector<float> n = terrain_normals_reference(t);  // world frame: x east, y up, z south
  const MapFrame map(t);
  write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f,
                 "# runnel terrain, %d x %d vertices, cell %.9g m, map frame (x east, y north, "
                 "z up)\n",
                 t.nx, t.ny, t.cell);
    for (int j = 0; j < t.ny; ++j) {
      for (int i = 0; i < t.nx; ++i)
        std::fprintf(f, "v %.17g %.17g %.9g\n", map.x(i * t.cell), map.y(j * t.cell), t.at(i, j));
    }
    for (std::size_t k = 0; k < t.size(); ++k)
      std::fprintf(f, "vn %.6f %.6f %.6f\n", n[3 * k], -n[3 * k + 2], n[3 * k + 1]);
    for (int j = 0; j + 1 < t.ny; ++j) {
      for (int i = 0; i + 1 < t.nx; ++i) {
        const long a = static_cast<long>(j) * t.nx + i + 1, b = a + 1, c = a + t.nx + 1,
                   d = a + t.nx;
        std::fprintf(f, "f %ld//%ld %ld//%ld %ld//%ld\n", a, a, c, c, b, b);
        std::fprintf(f, "f %ld//%ld %ld//%ld %ld//%ld\n", a, a, d, d, c, c);
      }
    }
    if (std::ferror(f)) throw runtime_error(path + ": write failed");
  });
}

// A checkpoint as one NetCDF time: the heights, their change from the initial terrain and, for a
// grid model with water, its depth.
void write_checkpoint_netcdf(const std::string& path, const CheckpointData& d) {
  NetcdfFrame frame;
  frame.time = d.time;
  frame.fields.emplace_back("height", d.terrain.h);
  std::vector<float> change(d.terrain.h.size());  // from the exact heights: no cancellation
  for (std::size_t k = 0; k < change.size(); ++k)
    change[k] = static_cast<float>(static_cast<double>(d.height_fixed[k] - d.initial_fixed[k]) *
                                   d.height_quantum);
  frame.fields.emplace_back("dh", change);
  for (const StoredField& f : d.fields)
    if (f.name == kSurfaceWaterDepth) frame.fields.emplace_back("water_depth", f.f32);
  write_netcdf(path, d.terrain, time_units(model_entry(d.model).info().clock), {frame});
}

// The grid a series says its frames stand on: a regular raster of one cell size in both
// directions, x rising east and y falling south (an edited or damaged file is refused, not
// written as it is).
void check_series_grid(const std::string& path, const std::vector<double>& x,
                       const std::vector<double>& y, std::size_t nx, std::size_t ny, double cell) {
  if (!(std::isfinite(cell) && cell > 0))
    throw input_error(path + ": /grid/x does not rise from column to column (cell " +
                      format_number(cell) + ")");
  const double tolerance = 1e-6 * cell;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const std::size_t k = j * nx + i;
      if (!(std::fabs(x[k] - (x[0] + cell * static_cast<double>(i))) <= tolerance &&
            std::fabs(y[k] - (y[0] - cell * static_cast<double>(j))) <= tolerance))
        throw input_error(path + ": /grid is not a regular raster of " + format_number(cell) +
                          " m cells at column " + std::to_string(i) + ", row " + std::to_string(j));
    }
}

// The frames' steps and times rise strictly and are finite, there is at least one, and all of them
// fit in memory (a file listing one frame 300,000 times is refused, not expanded).
void check_series_frames(const std::string& path, const std::vector<std::int64_t>& steps,
                         const std::vector<double>& times, const Heightmap& grid) {
  if (steps.empty())
    throw input_error(path + ": holds no terrain frames (a run writes them with --series-every N)");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (!std::isfinite(times[k]))
      throw input_error(path + ": frame " + std::to_string(k) + " has the time " +
                        format_number(times[k]));
    if (k > 0 && !(steps[k] > steps[k - 1] && times[k] > times[k - 1]))
      throw input_error(path + ": frame " + std::to_string(k) + " (step " +
                        std::to_string(steps[k]) +
                        ") does not come after the one before it: steps and times must rise");
  }
  const double bytes =
      static_cast<double>(steps.size()) * static_cast<double>(grid.size()) * 3 * sizeof(float);
  const MemoryRoom room = memory_room();
  if (room.bytes > 0 && bytes > room.bytes)
    throw input_error(path + ": " + std::to_string(steps.size()) + " frames of " +
                      std::to_string(grid.nx) + " x " + std::to_string(grid.ny) + " need about " +
                      format_number(bytes / 1e9) + " GB; " + room.limited_by + " leaves " +
                      format_number(room.bytes / 1e9) + " GB");
}

// A run's series.h5 as one NetCDF with a time axis: every terrain frame's height, Δh and water
// depth (docs/series.md).
void write_series_netcdf(const std::string& path, const std::string& series_path) {
  const H5File series = H5File::open_read(series_path);
  const std::vector<hsize_t> dims = series.dims("/grid/x");
  if (dims.size() != 2 || dims[0] < 2 || dims[1] < 2)
    throw input_error(series_path + ": /grid/x is not a grid");
  const std::vector<double> x = series.read_double("/grid/x", dims),
                            y = series.read_double("/grid/y", dims);
  Heightmap grid(static_cast<int>(dims[1]), static_cast<int>(dims[0]), x[1] - x[0]);
  check_series_grid(series_path, x, y, dims[1], dims[0], grid.cell);
  grid.origin_x = x[0] - 0.5 * grid.cell;  // the vertices stand at their pixels' centres
  grid.origin_z = y.back() - 0.5 * grid.cell;
  grid.georef.crs_wkt = series.read_string_attribute("/grid", "crs_wkt");
  const std::vector<std::int64_t> steps = series.read_int64("/height_step");
  const std::vector<double> times = series.read_double("/height_time", {steps.size()});
  check_series_frames(series_path, steps, times, grid);
  std::vector<NetcdfFrame> frames;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    char group[48];
    std::snprintf(group, sizeof group, "/terrain/%010lld", static_cast<long long>(steps[k]));
    NetcdfFrame frame;
    frame.time = times[k];
    for (auto [stored, name] : {std::pair{"height", "height"}, std::pair{"dh", "dh"},
                                std::pair{"depth", "water_depth"}}) {
      const std::string dataset = std::string(group) + "/" + stored;
      if (series.exists(dataset)) frame.fields.emplace_back(name, series.read_float(dataset, dims));
    }
    if (frame.fields.empty())
      throw input_error(series_path + ": frame " + std::to_string(steps[k]) + " has no " +
                        std::string(group) + " (a series written before frames had their own)");
    frames.push_back(std::move(frame));
  }
  const std::string units = series.has_attribute("/", "time_units")
                                ? series.read_string_attribute("/", "time_units")
                                : "s";
  write_netcdf(path, grid, units, frames);
}

bool is_series(const std::string& path) {
  const H5File file = H5File::open_read(path);
  return file.exists("/height_step") && file.exists("/grid");
}

}  // namespace

void add_export_command(CLI::App& app) {
  struct Options {
    std::string file, format, output, range;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "export",
      "Export the terrain of a checkpoint (.h5) as asc, png, npy, tif, obj or netcdf, or its SPH "
      "particles as ply (binary PLY in the map frame, for splashsurf and ParaView); or a run's "
      "series.h5 as one NetCDF with a time axis (--format netcdf)");
  cmd->add_option("checkpoint", opt->file, "checkpoint file (.h5), or series.h5 for netcdf")
      ->required();
  cmd->add_option("--format", opt->format,
                  "asc, png, npy, tif (GeoTIFF), obj (a triangle mesh), netcdf (CF-1.8 NetCDF-4, "
                  ".nc: height, dh, water depth; xarray, GDAL, QGIS) or ply (the particles)")
      ->required()
      ->check(CLI::IsMember({"asc", "png", "npy", "tif", "obj", "ply", "netcdf"}));
  cmd->add_option("-o,--output", opt->output, "file to write")->required();
  cmd->add_option("--range", opt->range, "png: heights MIN:MAX in metres mapped to 0..65535");
  cmd->callback([opt] {
    if (!opt->range.empty() && opt->format != "png")
      throw input_error("--range: only a png export has a height range (--format " + opt->format +
                        ")");
    check_output_paths({{"checkpoint", opt->file}}, {{"-o", opt->output}});
    require_output_folders({{"-o", opt->output}});
    if (opt->format == "netcdf") {
      if (std::filesystem::path(opt->output).extension() != ".nc")
        throw input_error("-o " + opt->output + ": a NetCDF file is named .nc");
      if (is_series(opt->file)) {
        write_series_netcdf(opt->output, opt->file);
      } else {
        write_checkpoint_netcdf(opt->output, read_checkpoint(opt->file));
      }
      std::fprintf(stderr, "runnel: wrote %s\n", terminal_safe(opt->output).c_str());
      return;
    }
    const CheckpointData data = read_checkpoint(opt->file);
    if (opt->format == "ply") {
      write_particles_ply(opt->output, data);
      std::fprintf(stderr, "runnel: wrote %s (%zu particles, step %llu)\n",
                   terminal_safe(opt->output).c_str(), data.particles.size(),
                   static_cast<unsigned long long>(data.steps));
      return;
    }
    if (opt->format == "obj") {
      write_obj(opt->output, data.terrain);
    } else {
      // The extension must agree with the format, so the file reads back as what it is.
      if (terrain_format_from_path(opt->output) != terrain_format_from_path("x." + opt->format)) {
        throw input_error("-o " + opt->output + ": the extension does not match --format " +
                          opt->format);
      }
      WriteOptions write;
      if (!opt->range.empty()) write.png_range = parse_range(opt->range, "--range");
      write_terrain(opt->output, data.terrain, write);
    }
    std::fprintf(stderr, "runnel: wrote %s (%d x %d vertices, step %llu)\n",
                 terminal_safe(opt->output).c_str(), data.terrain.nx, data.terrain.ny,
                 static_cast<unsigned long long>(data.steps));
  });
}

}  // namespace runnel::cli
