// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/terrain/netcdf_io.hpp"

namespace runnel {

// A run's series.h5 as a NetCDF export reads it: the grid (a regular raster, checked), the time
// units and every terrain frame's height, Δh and water depth. A series it cannot trust (an edited
// grid, non-finite or falling times, repeated frames, no terrain frame, more frames than memory
// holds) is an input error naming the file.
struct SeriesForNetcdf {
  Heightmap grid;  // heights unset: the frames carry them
  std::string time_units;
  std::vector<NetcdfFrame> frames;
};
SeriesForNetcdf read_series_for_netcdf(const std::string& series_path);

// The series as one NetCDF with a time axis (docs/series.md); the read runs first in a child
// process, so a file that crashes libhdf5 is refused, not fatal.
void write_series_netcdf(const std::string& path, const std::string& series_path);

}  // namespace runnel
