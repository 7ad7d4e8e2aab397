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
#include "runnel/models/registry.hpp"
#include "runnel/sim/particle_export.hpp"
#include "runnel/sim/series.hpp"
#include "runnel/sim/series_netcdf.hpp"
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
      "particles as ply (binary PLY in the map frame, for splashsurf and MeshLab) or vtp (VTK "
      "PolyData: ParaView draws and colours them); or a run's "
      "series.h5 as one NetCDF with a time axis (--format netcdf)");
  cmd->add_option("checkpoint", opt->file, "checkpoint file (.h5), or series.h5 for netcdf")
      ->required();
  cmd->add_option("--format", opt->format,
                  "asc, png, npy, tif (GeoTIFF), obj (a triangle mesh), netcdf (CF-1.8 NetCDF-4, "
                  ".nc: height, dh, water depth; xarray, GDAL, QGIS), ply or vtp (the particles)")
      ->required()
      ->check(CLI::IsMember({"asc", "png", "npy", "tif", "obj", "ply", "vtp", "netcdf"}));
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
    if (opt->format == "ply" || opt->format == "vtp") {
      if (std::filesystem::path(opt->output).extension() != "." + opt->format)
        throw input_error("-o " + opt->output + ": a " + opt->format + " file is named ." +
                          opt->format);
      if (opt->format == "ply")
        write_particles_ply(opt->output, data);
      else
        write_particles_vtp(opt->output, data);
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
