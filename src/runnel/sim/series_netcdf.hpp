// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/terrain/netcdf_io.hpp"

namespace runnel {

class H5File;

// What a NetCDF export reads of a run's series.h5 before the frames: the grid (a regular raster,
// checked), the time units, the terrain frames' steps and times, and the fields every frame holds
// (height, dh, water_depth). A series it cannot trust (an edited grid, non-finite or falling times,
// repeated frames, no terrain frame, frames of other fields) is an input error naming the file.
struct SeriesForNetcdf {
  Heightmap grid;  // heights unset: the frames carry them
  std::string time_units;
  std::vector<std::int64_t> steps;
  std::vector<double> times;
  std::vector<std::string> fields;
};
SeriesForNetcdf read_series_for_netcdf(const std::string& series_path);
// One field of one frame, as NetCDF names it.
std::vector<float> read_series_field(const H5File& series, const SeriesForNetcdf& s,
                                     std::size_t frame, const std::string& field);

// The series as one NetCDF with a time axis (docs/series.md), written a frame at a time (a long
// series never sits in memory whole); the read runs first in a child process, so a file that
// crashes libhdf5 is refused, not fatal.
void write_series_netcdf(const std::string& path, const std::string& series_path);

}  // namespace runnel
