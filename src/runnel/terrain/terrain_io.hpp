// SPDX-License-Identifier: MIT
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/text.hpp"

namespace runnel {

// What a reader does with NODATA holes in an ASCII grid (docs/terrain-formats.md).
enum class NodataPolicy {
  kFill,    // fill each hole with the mean of its valid neighbours, growing inwards; warn on stderr
  kRefuse,  // refuse the file
};

struct HeightRange {
  double min = 0.0;
  double max = 0.0;
};

struct ReadOptions {
  NodataPolicy nodata = NodataPolicy::kFill;
  std::optional<HeightRange> png_range;  // overrides the range stored in a runnel PNG
  std::optional<double> cell;            // overrides the cell size, a file's own included
  double cell_if_none = 1.0;  // the cell size of a file that carries none (NPY, a foreign PNG)
  // What the values are, for the messages: a terrain's heights, or a vertex raster's quantity.
  std::string quantity = "height", unit = " m";
  // NPY's NaN is a terrain's NODATA hole (under `nodata`); a vertex raster (a water depth, a mask)
  // refuses it as a value that is not a number.
  bool npy_nan_is_nodata = true;
};

struct WriteOptions {
  std::optional<HeightRange> png_range;  // default: the terrain's own min and max
};

// kGeoTiff: .tif/.tiff, read and written through GDAL with the georeferencing; kGdal: other
// rasters GDAL reads (.vrt .img .hgt .dem .bil .flt .grd .nc), read only.
enum class TerrainFormat { kAsc, kPng, kNpy, kGeoTiff, kGdal };

// What every terrain read or written must satisfy: heights finite and within ±1e7 m (the deepest
// trench is 11 km; far beyond, the fixed-point heights lose their headroom), the cell size within
// terrain.cell's range, the origin a finite coordinate.
inline constexpr double kMaxAbsHeight = 1e7;              // m
inline constexpr double kMinCell = 1e-6, kMaxCell = 1e6;  // m
inline constexpr double kMaxAbsOrigin = 1e12;             // m
void check_terrain_values(const std::string& path, const Heightmap& terrain,
                          const std::string& quantity = "height", const std::string& unit = " m");
// Its parts for a single value (a setter): the cell size, the origin.
void check_cell_size(const std::string& path, double cell);
void check_origin(const std::string& path, double origin_x, double origin_z);
void check_height_range(const std::string& path, const HeightRange& range);

// The format from the file name's extension (.asc, .png, .npy, .tif, ...; any case). Throws an
// input error.
TerrainFormat terrain_format_from_path(const std::string& path);

// Readers validate everything and throw runnel::Error (exit code 2) naming the file and the reason.
Heightmap read_terrain(const std::string& path, const ReadOptions& options = {});
// Why a vertex raster's value is refused ("" when it is fine), e.g. "a depth is 0 or more".
using VertexValueCheck = std::function<std::string(float)>;
// A raster on a terrain's vertices (masks, layer thicknesses, depths, graph inputs): read in any
// terrain format, every value checked by `check` (an input error naming `what`, the value and the
// reason). One of another size is resampled bilinearly (corner vertices onto corner vertices), with
// a warning on stderr naming `what`, printed once every check has passed; one of another shape
// (its columns more than one, or 1 %, from what the terrain's aspect gives its rows: resampling
// would stretch it) is refused. Given `terrain`, a raster georeferenced in the same CRS must cover
// the terrain's extent (within a cell), or it is refused with both extents.
std::vector<float> read_vertex_raster(const std::string& path, int nx, int ny,
                                      const std::string& what, const VertexValueCheck& check = {},
                                      const Heightmap* terrain = nullptr);

// Writers write atomically (temporary file, then rename).
void write_terrain(const std::string& path, const Heightmap& terrain,
                   const WriteOptions& options = {});

// The individual formats.
Heightmap read_asc(const std::string& path, NodataPolicy nodata);
void write_asc(const std::string& path, const Heightmap& terrain);
Heightmap read_png16(const std::string& path, const std::optional<HeightRange>& range,
                     double cell_if_none = 1.0);
void write_png16(const std::string& path, const Heightmap& terrain,
                 const std::optional<HeightRange>& range);
// NPY has no NODATA value: NaN marks a hole both ways (read with `nodata`'s policy; written at the
// terrain's holes).
Heightmap read_npy(const std::string& path, double cell_if_none = 1.0,
                   NodataPolicy nodata = NodataPolicy::kFill);
// The array's values as they are, NaN included (read_terrain's checks then refuse it).
Heightmap read_npy_values(const std::string& path, double cell_if_none = 1.0);
void write_npy(const std::string& path, const Heightmap& terrain);
// Any raster GDAL reads, band 1, with its CRS (which must be projected in metres), geotransform
// (north-up, square pixels) and NODATA value; GeoTIFF out, float32, DEFLATE-compressed.
Heightmap read_gdal(const std::string& path, NodataPolicy nodata);
void write_geotiff(const std::string& path, const Heightmap& terrain);
// The name of a CRS given as WKT ("WGS 84 / UTM zone 16N"); "none" for an empty one.
std::string crs_name(const std::string& wkt);

// Shared validation for every reader: sizes within limits.
void check_terrain_size(const std::string& path, long long nx, long long ny);
// Shared validation: every height finite. Reports the first offending vertex.
void check_finite_heights(const std::string& path, const Heightmap& terrain);
// Fills NaN holes (marked as NaN) from their neighbours. Returns the number filled.
long long fill_holes(Heightmap& terrain);
// What a reader does with the `holes` NODATA cells it marked as NaN: refuses the file, or fills
// them and says so on stderr.
// The heights as a raster with a NODATA value writes them: `nodata` where the source had holes.
std::vector<float> heights_with_holes(const Heightmap& terrain, float nodata);
void apply_nodata_policy(const std::string& path, Heightmap& terrain, long long holes,
                         NodataPolicy policy);

}  // namespace runnel
