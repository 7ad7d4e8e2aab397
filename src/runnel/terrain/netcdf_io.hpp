// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// One time of a NetCDF export: the model time and its fields on the terrain's grid (ny × nx, row 0
// the northern row), by name: "height" always, "dh" and "water_depth" where known.
struct NetcdfFrame {
  double time = 0;
  std::vector<std::pair<std::string, std::vector<float>>> fields;
};

// Writes a CF-1.8 NetCDF-4 file (docs/terrain-formats.md, "NetCDF"), atomically: dimensions time,
// y, x; coordinates x and y at the pixels' centres in the terrain's map coordinates (y from north
// to south, as the rows run), time in `time_units` ("s", "yr" or "1"); the CRS as the grid
// mapping variable spatial_ref (crs_wkt and spatial_ref attributes, as GDAL and rioxarray read
// it); each field a (time, y, x) float32 variable with its units, the terrain's NODATA holes as
// its _FillValue. xarray, GDAL, QGIS and Landlab read it.
void write_netcdf(const std::string& path, const Heightmap& grid, const std::string& time_units,
                  const std::vector<NetcdfFrame>& frames);

// The frames of an export read one field of one frame at a time as they are written, so that a
// long series never sits in memory whole: the times, the fields every frame has, and the reader.
struct NetcdfFrameSource {
  std::vector<double> times;
  std::vector<std::string> fields;
  std::function<std::vector<float>(std::size_t frame, const std::string& field)> read;
};
void write_netcdf(const std::string& path, const Heightmap& grid, const std::string& time_units,
                  const NetcdfFrameSource& frames);

}  // namespace runnel
