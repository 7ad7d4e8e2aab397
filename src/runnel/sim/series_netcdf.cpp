// SPDX-License-Identifier: MIT
#include "runnel/sim/series_netcdf.hpp"

#include <cmath>
#include <cstdio>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/crash_isolated_read.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/memory_check.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

constexpr hsize_t kMostSeriesFrames = 10000000;  // a frame a step for 10^7 steps

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

}  // namespace

SeriesForNetcdf read_series_for_netcdf(const std::string& series_path) {
  SeriesForNetcdf out;
  const H5File series = H5File::open_read(series_path);
  const std::vector<hsize_t> dims = series.dims("/grid/x");
  if (dims.size() != 2 || dims[0] < 2 || dims[1] < 2)
    throw input_error(series_path + ": /grid/x is not a grid");
  check_terrain_size(series_path, static_cast<long long>(dims[1]), static_cast<long long>(dims[0]));
  if (series.dims("/grid/y") != dims)
    throw input_error(series_path + ": /grid/y is not /grid/x's shape");
  const std::vector<hsize_t> listed = series.dims("/height_step");
  if (listed.size() != 1 || listed[0] > kMostSeriesFrames)
    throw input_error(series_path + ": /height_step lists more than " +
                      std::to_string(kMostSeriesFrames) + " frames, or is not a list");
  const std::vector<double> x = series.read_double("/grid/x", dims),
                            y = series.read_double("/grid/y", dims);
  Heightmap& grid = out.grid;
  grid = Heightmap(static_cast<int>(dims[1]), static_cast<int>(dims[0]), x[1] - x[0]);
  check_series_grid(series_path, x, y, dims[1], dims[0], grid.cell);
  grid.origin_x = x[0] - 0.5 * grid.cell;  // the vertices stand at their pixels' centres
  grid.origin_z = y.back() - 0.5 * grid.cell;
  grid.georef.crs_wkt = series.read_string_attribute("/grid", "crs_wkt");
  const std::vector<std::int64_t> steps = series.read_int64("/height_step");
  const std::vector<double> times = series.read_double("/height_time", {steps.size()});
  check_series_frames(series_path, steps, times, grid);
  std::vector<NetcdfFrame>& frames = out.frames;
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
  out.time_units = series.has_attribute("/", "time_units")
                       ? series.read_string_attribute("/", "time_units")
                       : "s";
  return out;
}

void write_series_netcdf(const std::string& path, const std::string& series_path) {
  // libhdf5 crashes on some damaged files instead of reporting them: the read runs once in a child.
  refuse_if_reading_crashes(series_path, [&] { read_series_for_netcdf(series_path); });
  const SeriesForNetcdf s = read_series_for_netcdf(series_path);
  write_netcdf(path, s.grid, s.time_units, s.frames);
}

}  // namespace runnel
