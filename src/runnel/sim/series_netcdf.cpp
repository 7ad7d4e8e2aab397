// SPDX-License-Identifier: MIT
#include "runnel/sim/series_netcdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/crash_isolated_read.hpp"
#include "runnel/io/georeference_h5.hpp"
#include "runnel/io/hdf5_file.hpp"
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

// The frames' steps and times rise strictly and are finite, and there is at least one (a file
// listing one frame 300,000 times is refused, not expanded).
void check_series_frames(const std::string& path, const std::vector<std::int64_t>& steps,
                         const std::vector<double>& times) {
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
}

// The stored name of each exported field in a frame's group.
constexpr std::pair<const char*, const char*> kSeriesFields[] = {
    {"height", "height"}, {"dh", "dh"}, {"depth", "water_depth"}};

std::string frame_group(std::int64_t step) {
  char group[48];
  std::snprintf(group, sizeof group, "/terrain/%010lld", static_cast<long long>(step));
  return group;
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
  read_georeference(series, series_path, "/grid", grid);
  out.steps = series.read_int64("/height_step");
  out.times = series.read_double("/height_time", {out.steps.size()});
  check_series_frames(series_path, out.steps, out.times);
  // Every frame holds the same fields, as the first one (their data is read as it is written).
  for (auto [stored, name] : kSeriesFields)
    if (series.exists(frame_group(out.steps.front()) + "/" + stored)) out.fields.push_back(name);
  for (std::size_t k = 0; k < out.steps.size(); ++k) {
    const std::string group = frame_group(out.steps[k]);
    if (out.fields.empty() || !series.exists(group))
      throw input_error(series_path + ": frame " + std::to_string(out.steps[k]) + " has no " +
                        group + " (a series written before frames had their own)");
    for (auto [stored, name] : kSeriesFields) {
      const bool listed =
          std::find(out.fields.begin(), out.fields.end(), std::string(name)) != out.fields.end();
      if (listed != series.exists(group + "/" + stored))
        throw input_error(series_path + ": frame " + std::to_string(out.steps[k]) +
                          " holds other fields than the first frame (" + stored + ")");
    }
  }
  out.time_units = series.has_attribute("/", "time_units")
                       ? series.read_string_attribute("/", "time_units")
                       : "s";
  return out;
}

std::vector<float> read_series_field(const H5File& series, const SeriesForNetcdf& s,
                                     std::size_t frame, const std::string& field) {
  for (auto [stored, name] : kSeriesFields)
    if (field == name)
      return series.read_float(frame_group(s.steps[frame]) + "/" + stored,
                               {static_cast<hsize_t>(s.grid.ny), static_cast<hsize_t>(s.grid.nx)});
  return {};
}

void write_series_netcdf(const std::string& path, const std::string& series_path) {
  // libhdf5 crashes on some damaged files instead of reporting them: the whole read runs once in a
  // child, a frame at a time.
  refuse_if_reading_crashes(series_path, [&] {
    const SeriesForNetcdf s = read_series_for_netcdf(series_path);
    const H5File series = H5File::open_read(series_path);
    for (std::size_t f = 0; f < s.steps.size(); ++f)
      for (const std::string& field : s.fields) read_series_field(series, s, f, field);
  });
  const SeriesForNetcdf s = read_series_for_netcdf(series_path);
  const H5File series = H5File::open_read(series_path);
  NetcdfFrameSource source;
  source.times = s.times;
  source.fields = s.fields;
  source.read = [&](std::size_t f, const std::string& field) {
    return read_series_field(series, s, f, field);
  };
  write_netcdf(path, s.grid, s.time_units, source);
}

}  // namespace runnel
