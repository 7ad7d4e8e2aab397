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

// The CF attributes of a CRS's grid mapping variable (grid_mapping_name, the projection's
// parameters, the ellipsoid), as GDAL's netCDF driver writes them, each a string or a number.
struct CfAttribute {
  std::string name;
  std::string text;  // a string attribute, or empty
  double number = 0;
  bool is_number = false;
};
std::vector<CfAttribute> cf_grid_mapping(const std::string& crs_wkt);

// The time coordinate's CF attributes for a model clock's units ("s", "yr" or "1"; name, value).
// Seconds are a CF time coordinate, "seconds since 1970-01-01 00:00:00" on the proleptic Gregorian
// calendar (a nominal epoch: the model's clock has no date); CF has no calendar of years (the
// checker refuses "years since"), so years are plain numbers in "a" (annum) and iterations in "1".
std::vector<std::pair<std::string, std::string>> cf_time_attributes(const std::string& time_units);

// Writes a CF-1.8 NetCDF-4 file (docs/terrain-formats.md, "NetCDF"), atomically: dimensions time,
// y, x; coordinates x and y at the pixels' centres in the terrain's map coordinates (y from north
// to south, as the rows run), time for a clock in `time_units` ("s", "yr" or "1":
// cf_time_attributes); the CRS as the grid mapping variable spatial_ref (cf_grid_mapping's
// attributes, and crs_wkt and spatial_ref, as GDAL and rioxarray read it); each field a (time, y,
// x) float32 variable with its units, the terrain's NODATA holes as its _FillValue. xarray, GDAL,
// QGIS and Landlab read it.
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
