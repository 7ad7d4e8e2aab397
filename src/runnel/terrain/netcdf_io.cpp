// SPDX-License-Identifier: MIT
// NetCDF out through GDAL's multidimensional API (its netCDF driver): no other library needed.
#include "runnel/terrain/netcdf_io.hpp"

#include <gdal_priv.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <random>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/gdal_support.hpp"

namespace runnel {

namespace {

struct FieldMeta {
  const char* name;
  const char* units;
  const char* long_name;
  const char* standard_name;  // CF standard name, or ""
};

constexpr FieldMeta kFields[] = {
    {"height", "m", "terrain height", "surface_altitude"},
    {"dh", "m", "height change from the initial terrain (erosion < 0, deposition > 0)", ""},
    {"water_depth", "m", "depth of the water on the surface", ""},
};

const FieldMeta& meta_of(const std::string& name) {
  for (const FieldMeta& m : kFields)
    if (name == m.name) return m;
  throw runtime_error("netcdf: no description of the field " + name);
}

void text_attribute(GDALIHasAttribute& owner, const std::string& name, const std::string& value) {
  auto attribute = owner.CreateAttribute(name, {}, GDALExtendedDataType::CreateString());
  if (!attribute || !attribute->Write(value.c_str()))
    throw runtime_error("netcdf: cannot write the attribute " + name + " (" + gdal_message() + ")");
}

void number_attribute(GDALIHasAttribute& owner, const std::string& name, double value,
                      GDALDataType type = GDT_Float64) {
  auto attribute = owner.CreateAttribute(name, {}, GDALExtendedDataType::Create(type));
  if (!attribute || !attribute->Write(value))
    throw runtime_error("netcdf: cannot write the attribute " + name + " (" + gdal_message() + ")");
}

std::shared_ptr<GDALMDArray> coordinate(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim,
                                        const std::vector<double>& values, const char* units,
                                        const char* standard_name, const char* axis,
                                        const char* long_name) {
  auto array = root.CreateMDArray(dim->GetName(), {dim}, GDALExtendedDataType::Create(GDT_Float64));
  if (!array) throw runtime_error("netcdf: cannot create " + dim->GetName());
  const GUInt64 start = 0;
  const size_t count = values.size();
  if (!array->Write(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64),
                    values.data()))
    throw runtime_error("netcdf: cannot write " + dim->GetName() + " (" + gdal_message() + ")");
  text_attribute(*array, "units", units);
  if (*standard_name) text_attribute(*array, "standard_name", standard_name);
  if (*axis) text_attribute(*array, "axis", axis);
  text_attribute(*array, "long_name", long_name);
  return array;
}

void write_file(const std::string& path, const Heightmap& grid, const std::string& time_units,
                const NetcdfFrameSource& frames) {
  init_gdal();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
  if (!driver) throw runtime_error(path + ": this GDAL has no netCDF driver");
  const char* options[] = {"FORMAT=NC4", nullptr};
  std::unique_ptr<GDALDataset> dataset(
      driver->CreateMultiDimensional(path.c_str(), nullptr, const_cast<char**>(options)));
  if (!dataset) throw runtime_error(path + ": cannot create (" + gdal_message() + ")");
  auto root = dataset->GetRootGroup();
  text_attribute(*root, "Conventions", "CF-1.8");
  text_attribute(*root, "title", "runnel terrain");
  text_attribute(*root, "source", "runnel");

  const auto nx = static_cast<GUInt64>(grid.nx), ny = static_cast<GUInt64>(grid.ny);
  auto time = root->CreateDimension("time", GDAL_DIM_TYPE_TEMPORAL, "", frames.times.size());
  auto y = root->CreateDimension("y", GDAL_DIM_TYPE_HORIZONTAL_Y, "", ny);
  auto x = root->CreateDimension("x", GDAL_DIM_TYPE_HORIZONTAL_X, "", nx);
  if (!time || !y || !x) throw runtime_error(path + ": cannot create the dimensions");
  const MapFrame map(grid);
  std::vector<double> xs(grid.nx), ys(grid.ny);
  for (int i = 0; i < grid.nx; ++i) xs[i] = map.x(i * grid.cell);
  for (int j = 0; j < grid.ny; ++j) ys[j] = map.y(j * grid.cell);
  const bool projected = !grid.georef.crs_wkt.empty();
  coordinate(*root, x, xs, "m", projected ? "projection_x_coordinate" : "", "X",
             "easting of the pixel centres");
  coordinate(*root, y, ys, "m", projected ? "projection_y_coordinate" : "", "Y",
             "northing of the pixel centres");
  auto t = root->CreateMDArray("time", {time}, GDALExtendedDataType::Create(GDT_Float64));
  if (!t) throw runtime_error(path + ": cannot create time");
  const GUInt64 start = 0;
  const size_t count = frames.times.size();
  if (!t->Write(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64),
                frames.times.data()))
    throw runtime_error(path + ": cannot write time (" + gdal_message() + ")");
  for (const auto& [name, value] : cf_time_attributes(time_units)) text_attribute(*t, name, value);

  // The CRS as CF's grid mapping variable, named as rioxarray and GDAL name it.
  if (projected) {
    auto crs = root->CreateMDArray("spatial_ref", {}, GDALExtendedDataType::Create(GDT_Int32));
    if (!crs) throw runtime_error(path + ": cannot create spatial_ref");
    for (const CfAttribute& a : cf_grid_mapping(grid.georef.crs_wkt)) {
      if (a.is_number) {
        number_attribute(*crs, a.name, a.number);
      } else {
        text_attribute(*crs, a.name, a.text);
      }
    }
    text_attribute(*crs, "crs_wkt", grid.georef.crs_wkt);
    text_attribute(*crs, "spatial_ref", grid.georef.crs_wkt);
  }
  if (frames.times.empty()) return;
  const float fill = static_cast<float>(grid.georef.nodata.value_or(NAN));
  for (const std::string& name : frames.fields) {
    const FieldMeta& meta = meta_of(name);
    auto array = root->CreateMDArray(name, {time, y, x}, GDALExtendedDataType::Create(GDT_Float32));
    if (!array) throw runtime_error(path + ": cannot create " + name);
    if (!grid.georef.holes.empty()) {
      number_attribute(*array, "_FillValue", fill, GDT_Float32);
    }
    text_attribute(*array, "units", meta.units);
    text_attribute(*array, "long_name", meta.long_name);
    if (*meta.standard_name) text_attribute(*array, "standard_name", meta.standard_name);
    if (projected) text_attribute(*array, "grid_mapping", "spatial_ref");
    for (std::size_t f = 0; f < frames.times.size(); ++f) {
      std::vector<float> values = frames.read(f, name);
      if (values.size() != grid.size())
        throw runtime_error(path + ": frame " + std::to_string(f) + " lacks the field " + name);
      for (std::size_t v = 0; v < values.size(); ++v)
        if (grid.georef.hole(v)) values[v] = fill;
      const GUInt64 start[3] = {f, 0, 0};
      const size_t count[3] = {1, static_cast<size_t>(ny), static_cast<size_t>(nx)};
      if (!array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32),
                        values.data()))
        throw runtime_error(path + ": cannot write " + name + " (" + gdal_message() + ")");
    }
  }
}

}  // namespace

std::vector<CfAttribute> cf_grid_mapping(const std::string& crs_wkt) {
  init_gdal();
  OGRSpatialReference srs;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (srs.importFromWkt(crs_wkt.c_str()) != OGRERR_NONE)
    throw runtime_error("netcdf: the terrain's CRS is not WKT GDAL reads");
  // GDAL 3.6 turns a CRS into CF attributes only inside its netCDF driver: a one-value variable
  // with the CRS is written to a scratch file, and its grid mapping variable's attributes read
  // back.
  std::random_device entropy;
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() /
      ("runnel-crs-" + std::to_string(entropy()) + std::to_string(entropy()) + ".nc");
  std::vector<CfAttribute> out;
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
    if (!driver) throw runtime_error("netcdf: this GDAL has no netCDF driver");
    std::unique_ptr<GDALDataset> dataset(
        driver->CreateMultiDimensional(scratch.c_str(), nullptr, nullptr));
    if (!dataset)
      throw runtime_error("netcdf: cannot write a scratch file in " +
                          scratch.parent_path().string() + " (" + gdal_message() + ")");
    auto root = dataset->GetRootGroup();
    auto one = root->CreateDimension("one", "", "", 1);
    auto value = root->CreateMDArray("value", {one}, GDALExtendedDataType::Create(GDT_Byte));
    if (!value || !value->SetSpatialRef(&srs))
      throw runtime_error("netcdf: GDAL cannot write this CRS as CF (" + gdal_message() + ")");
  }
  {
    std::unique_ptr<GDALDataset> dataset(GDALDataset::Open(
        scratch.c_str(), GDAL_OF_MULTIDIM_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    auto root = dataset ? dataset->GetRootGroup() : nullptr;
    auto value = root ? root->OpenMDArray("value") : nullptr;
    auto mapping = value ? value->GetAttribute("grid_mapping") : nullptr;
    auto variable = mapping ? root->OpenMDArray(mapping->ReadAsString()) : nullptr;
    if (variable) {
      for (const auto& a : variable->GetAttributes()) {
        const std::string& name = a->GetName();
        if (name == "spatial_ref" || name == "crs_wkt" || name == "long_name") continue;
        CfAttribute c{name, "", 0, false};
        if (a->GetDataType().GetClass() == GEDTC_STRING) {
          c.text = a->ReadAsString() ? a->ReadAsString() : "";
        } else {
          c.number = a->ReadAsDouble();
          c.is_number = true;
        }
        out.push_back(c);
      }
    }
  }
  std::error_code ignored;
  std::filesystem::remove(scratch, ignored);
  if (out.empty()) throw runtime_error("netcdf: GDAL gave no CF grid mapping for this CRS");
  return out;
}

std::vector<std::pair<std::string, std::string>> cf_time_attributes(const std::string& time_units) {
  if (time_units == "s")
    return {{"units", "seconds since 1970-01-01 00:00:00"},
            {"calendar", "proleptic_gregorian"},
            {"standard_name", "time"},
            {"axis", "T"},
            {"long_name", "model time (the run's clock, on a nominal epoch)"}};
  if (time_units == "yr") return {{"units", "a"}, {"long_name", "model time in years"}};
  return {{"units", "1"}, {"long_name", "model iterations"}};
}

void write_netcdf(const std::string& path, const Heightmap& grid, const std::string& time_units,
                  const std::vector<NetcdfFrame>& frames) {
  NetcdfFrameSource source;
  for (const NetcdfFrame& f : frames) source.times.push_back(f.time);
  if (!frames.empty())
    for (const auto& [name, values] : frames.front().fields) source.fields.push_back(name);
  source.read = [&](std::size_t f, const std::string& name) {
    for (const auto& [field, values] : frames[f].fields)
      if (field == name) return values;
    return std::vector<float>();
  };
  write_netcdf(path, grid, time_units, source);
}

void write_netcdf(const std::string& path, const Heightmap& grid, const std::string& time_units,
                  const NetcdfFrameSource& frames) {
  write_path_atomically(path, [&](const std::string& temporary) {
    CPLErrorReset();
    write_file(temporary, grid, time_units, frames);  // the dataset is closed when it returns
    if (CPLGetLastErrorType() == CE_Failure)
      throw runtime_error(path + ": write failed (" + gdal_message() + ")");
  });
}

}  // namespace runnel
