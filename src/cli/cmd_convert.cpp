// SPDX-License-Identifier: MIT
// runnel convert: between the terrain formats (.asc, .png, .npy, .tif), formats from the
// extensions.
#include <cstdio>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"

namespace runnel::cli {

void add_convert_command(CLI::App& app) {
  struct Options {
    std::string input, output, range, nodata = "fill";
    double cell = 0.0;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("convert",
                         "Convert a terrain between ESRI ASCII grid (.asc), 16-bit PNG (.png), "
                         "NumPy (.npy) and GeoTIFF (.tif; any raster GDAL reads as input); formats "
                         "from the extensions. The georeferencing is kept where the output can "
                         "hold it: GeoTIFF keeps the CRS, corner, cell size and NODATA value, ASC "
                         "the corner and cell size");
  cmd->add_option("input", opt->input, "terrain to read")->required();
  cmd->add_option("output", opt->output, "terrain to write")->required();
  cmd->add_option("--range", opt->range,
                  "PNG heights MIN:MAX in metres: how a PNG input is read, and the range a "
                  "PNG output is quantised to (default: stored in runnel PNGs / the terrain's)");
  cmd->add_option("--cell", opt->cell,
                  "cell size in metres (NPY and foreign PNG carry none; default 1)")
      ->check(cell_size());
  cmd->add_option("--nodata", opt->nodata, "ASC NODATA cells: fill (from neighbours) or refuse")
      ->check(CLI::IsMember({"fill", "refuse"}))
      ->capture_default_str();
  cmd->callback([opt, cmd] {
    terrain_format_from_path(opt->output);  // fail on a bad output name before reading anything
    check_output_paths({{"input terrain", opt->input}}, {{"output terrain", opt->output}});
    require_output_folders({{"output terrain", opt->output}});
    const bool png = terrain_format_from_path(opt->input) == TerrainFormat::kPng ||
                     terrain_format_from_path(opt->output) == TerrainFormat::kPng;
    if (!opt->range.empty() && !png)
      throw input_error("--range: only a PNG input or output has a height range");
    ReadOptions read;
    WriteOptions write;
    read.nodata = opt->nodata == "refuse" ? NodataPolicy::kRefuse : NodataPolicy::kFill;
    if (cmd->count("--cell")) read.cell = opt->cell;
    if (!opt->range.empty()) {
      const HeightRange range = parse_range(opt->range, "--range");
      if (terrain_format_from_path(opt->input) == TerrainFormat::kPng) read.png_range = range;
      write.png_range = range;
    }
    const Heightmap terrain = read_terrain(opt->input, read);
    write_terrain(opt->output, terrain, write);
    std::fprintf(stderr, "runnel: %s -> %s (%d x %d vertices, cell %g m, heights %.3f..%.3f m)\n",
                 terminal_safe(opt->input).c_str(), terminal_safe(opt->output).c_str(), terrain.nx,
                 terrain.ny, terrain.cell, terrain.min_height(), terrain.max_height());
  });
}

}  // namespace runnel::cli
