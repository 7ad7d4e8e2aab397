// SPDX-License-Identifier: MIT
// GeoTIFF (and, for reading, any raster GDAL reads) with its georeferencing: the CRS, the
// geotransform and the NODATA value (docs/terrain-formats.md).
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/gdal_support.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

namespace {

struct DatasetCloser {
  void operator()(void* dataset) const {
    if (dataset) GDALClose(dataset);
  }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

struct SrsDestroyer {
  void operator()(void* srs) const { OSRDestroySpatialReference(srs); }
};

using Srs = std::unique_ptr<void, SrsDestroyer>;

// The spatial reference of a WKT text; null when it cannot be read.
Srs srs_from_wkt(const std::string& wkt) {
  Srs srs(OSRNewSpatialReference(nullptr));
  char* text = const_cast<char*>(wkt.c_str());
  if (OSRImportFromWkt(srs.get(), &text) != OGRERR_NONE) srs.reset();
  return srs;
}

// The WGS 84 UTM zone of a longitude and latitude (degrees), as an EPSG code: 326ZZ north of the
// equator, 327ZZ south.
int utm_epsg(double longitude, double latitude) {
  const int zone = std::clamp(static_cast<int>(std::floor((longitude + 180.0) / 6.0)) + 1, 1, 60);
  return (latitude >= 0 ? 32600 : 32700) + zone;
}

// Heights and cells are metres in runnel's physics, so a CRS must be projected in metres (or
// absent). `centre` is the raster's centre in its own coordinates (degrees when geographic), for
// the UTM zone a refusal suggests.
void check_crs(const std::string& path, const std::string& wkt, const double centre[2]) {
  if (wkt.empty()) return;
  const Srs srs = srs_from_wkt(wkt);
  if (!srs) throw input_error(path + ": its coordinate reference system could not be read");
  if (OSRIsGeographic(srs.get())) {
    const int epsg = utm_epsg(centre[0], centre[1]);
    throw input_error(
        path +
        ": geographic coordinates (degrees); runnel needs a projected CRS in metres: "
        "reproject it first, e.g. to the UTM zone of its centre: gdalwarp -t_srs EPSG:" +
        std::to_string(epsg) + " in.tif out.tif");
  }
  if (OSRIsProjected(srs.get()) || OSRIsLocal(srs.get())) {
    char* unit = nullptr;
    const double metres = OSRGetLinearUnits(srs.get(), &unit);
    if (std::fabs(metres - 1.0) > 1e-12) {
      throw input_error(path + ": its CRS measures in " + std::string(unit ? unit : "?") +
                        ", not metres; reproject it first (gdalwarp -t_srs ...)");
    }
  }
}

}  // namespace

std::string crs_name(const std::string& wkt) {
  if (wkt.empty()) return "none";
  const Srs srs = srs_from_wkt(wkt);
  if (!srs) return "unreadable";
  const char* name = OSRGetName(srs.get());
  return name ? name : "unnamed";
}

Heightmap read_gdal(const std::string& path, NodataPolicy nodata) {
  init_gdal();
  Dataset dataset(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!dataset) throw input_error(path + ": not a raster GDAL reads (" + gdal_message() + ")");
  if (GDALGetRasterCount(dataset.get()) < 1) throw input_error(path + ": the raster has no band");
  const long long nx = GDALGetRasterXSize(dataset.get()), ny = GDALGetRasterYSize(dataset.get());
  check_terrain_size(path, nx, ny);

  double transform[6];
  const bool georeferenced = GDALGetGeoTransform(dataset.get(), transform) == CE_None;
  Heightmap terrain(static_cast<int>(nx), static_cast<int>(ny), 1.0);
  const char* wkt = GDALGetProjectionRef(dataset.get());
  terrain.georef.crs_wkt = wkt ? wkt : "";
  // The centre in the raster's coordinates (GDAL's traditional order: x is the longitude).
  const double centre[2] = {
      georeferenced ? transform[0] + 0.5 * static_cast<double>(nx) * transform[1] : 0.0,
      georeferenced ? transform[3] + 0.5 * static_cast<double>(ny) * transform[5] : 0.0};
  check_crs(path, terrain.georef.crs_wkt, centre);
  if (georeferenced) {
    if (transform[2] != 0.0 || transform[4] != 0.0) {
      throw input_error(path + ": the raster is rotated (geotransform terms " +
                        format_number(transform[2]) + ", " + format_number(transform[4]) +
                        "); warp it north-up first (gdalwarp)");
    }
    if (!(transform[1] > 0.0 && transform[5] < 0.0)) {
      throw input_error(path + ": the raster is not north-up (pixel size " +
                        format_number(transform[1]) + " x " + format_number(transform[5]) +
                        "); warp it first (gdalwarp)");
    }
    if (std::fabs(transform[1] + transform[5]) > 1e-9 * transform[1]) {
      throw input_error(path + ": pixels of " + format_number(transform[1]) + " x " +
                        format_number(-transform[5]) +
                        " are not square; resample it first (gdalwarp -tr SIZE SIZE)");
    }
    terrain.cell = transform[1];
    terrain.origin_x = transform[0];
    terrain.origin_z = transform[3] + static_cast<double>(ny) * transform[5];
  }

  GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
  int has_nodata = 0;
  const double nodata_value = GDALGetRasterNoDataValue(band, &has_nodata);
  if (has_nodata) terrain.georef.nodata = nodata_value;
  std::vector<double> row(static_cast<std::size_t>(nx));
  long long holes = 0;
  for (int j = 0; j < terrain.ny; ++j) {
    if (GDALRasterIO(band, GF_Read, 0, j, terrain.nx, 1, row.data(), terrain.nx, 1, GDT_Float64, 0,
                     0) != CE_None) {
      throw input_error(path + ": row " + std::to_string(j) + " could not be read (" +
                        gdal_message() + ")");
    }
    for (int i = 0; i < terrain.nx; ++i) {
      const double v = row[static_cast<std::size_t>(i)];
      if ((has_nodata && (v == nodata_value || (std::isnan(v) && std::isnan(nodata_value))))) {
        ++holes;
        terrain.at(i, j) = std::nanf("");
        continue;
      }
      if (!(std::fabs(v) <= kMaxAbsHeight)) {
        throw input_error(path + ": height " + format_number(v) + " at column " +
                          std::to_string(i) + ", row " + std::to_string(j) +
                          " is not a finite number within ±" + format_number(kMaxAbsHeight) + " m");
      }
      terrain.at(i, j) = static_cast<float>(v);
    }
  }
  apply_nodata_policy(path, terrain, holes, nodata);
  return terrain;
}

void write_geotiff(const std::string& path, const Heightmap& terrain) {
  init_gdal();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver) throw runtime_error(path + ": this GDAL has no GeoTIFF driver");
  write_path_atomically(path, [&](const std::string& temporary) {
    CPLErrorReset();
    {
      // DEFLATE with the floating-point predictor: lossless, and about half the size of raw floats.
      const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=YES", nullptr};
      Dataset dataset(GDALCreate(driver, temporary.c_str(), terrain.nx, terrain.ny, 1, GDT_Float32,
                                 const_cast<char**>(options)));
      if (!dataset) throw runtime_error(path + ": cannot create (" + gdal_message() + ")");
      double transform[6] = {
          terrain.origin_x, terrain.cell, 0.0, terrain.origin_z + terrain.ny * terrain.cell, 0.0,
          -terrain.cell};
      GDALSetGeoTransform(dataset.get(), transform);
      if (!terrain.georef.crs_wkt.empty())
        GDALSetProjection(dataset.get(), terrain.georef.crs_wkt.c_str());
      GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
      if (terrain.georef.nodata) GDALSetRasterNoDataValue(band, *terrain.georef.nodata);
      std::vector<float> heights =
          terrain.georef.nodata
              ? heights_with_holes(terrain, static_cast<float>(*terrain.georef.nodata))
              : terrain.h;
      if (GDALRasterIO(band, GF_Write, 0, 0, terrain.nx, terrain.ny, heights.data(), terrain.nx,
                       terrain.ny, GDT_Float32, 0, 0) != CE_None) {
        throw runtime_error(path + ": write failed (" + gdal_message() + ")");
      }
    }  // closing the dataset writes the rest
    if (CPLGetLastErrorType() == CE_Failure)
      throw runtime_error(path + ": write failed (" + gdal_message() + ")");
  });
}

}  // namespace runnel
