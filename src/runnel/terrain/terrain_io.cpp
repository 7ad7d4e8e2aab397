// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/core/text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"

namespace runnel {

TerrainFormat terrain_format_from_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".asc") return TerrainFormat::kAsc;
  if (ext == ".png") return TerrainFormat::kPng;
  if (ext == ".npy") return TerrainFormat::kNpy;
  if (ext == ".tif" || ext == ".tiff") return TerrainFormat::kGeoTiff;
  for (const char* gdal : {".vrt", ".img", ".hgt", ".dem", ".bil", ".flt", ".grd", ".nc"})
    if (ext == gdal) return TerrainFormat::kGdal;
  throw input_error(path + ": unknown terrain format '" + ext +
                    "' (expected .asc, .png, .npy, .tif or a raster GDAL reads)");
}

Heightmap read_terrain(const std::string& path, const ReadOptions& options) {
  const TerrainFormat format = terrain_format_from_path(path);
  require_regular_input(path, "terrain file");
  Heightmap terrain;
  switch (format) {
    case TerrainFormat::kAsc:
      terrain = read_asc(path, options.nodata);
      break;
    case TerrainFormat::kPng:
      terrain = read_png16(path, options.png_range, options.cell_if_none);
      break;
    case TerrainFormat::kNpy:
      terrain = options.npy_nan_is_nodata ? read_npy(path, options.cell_if_none, options.nodata)
                                          : read_npy_values(path, options.cell_if_none);
      break;
    case TerrainFormat::kGeoTiff:
    case TerrainFormat::kGdal:
      terrain = read_gdal(path, options.nodata);
      break;
  }
  if (options.cell) terrain.cell = *options.cell;
  check_terrain_values(path, terrain, options.quantity, options.unit);
  return terrain;
}

void write_terrain(const std::string& path, const Heightmap& terrain, const WriteOptions& options) {
  // Never write what no reader would take back. (Grids of other quantities, such as the drainage
  // area in m², go through here too: finite, not a height's range.)
  if (!(terrain.cell >= kMinCell && terrain.cell <= kMaxCell))
    throw input_error(path + ": cell size " + format_number(terrain.cell) + " m is out of range");
  check_finite_heights(path, terrain);
  if (options.png_range) check_height_range(path, *options.png_range);
  switch (terrain_format_from_path(path)) {
    case TerrainFormat::kAsc:
      write_asc(path, terrain);
      break;
    case TerrainFormat::kPng:
      write_png16(path, terrain, options.png_range);
      break;
    case TerrainFormat::kNpy:
      write_npy(path, terrain);
      break;
    case TerrainFormat::kGeoTiff:
      write_geotiff(path, terrain);
      break;
    case TerrainFormat::kGdal:
      throw input_error(path +
                        ": runnel writes GeoTIFF (.tif), not this format; convert with "
                        "gdal_translate");
  }
}

void check_terrain_size(const std::string& path, long long nx, long long ny) {
  if (nx < 2 || ny < 2) {
    throw input_error(path + ": terrain of " + std::to_string(nx) + " x " + std::to_string(ny) +
                      " vertices is too small (at least 2 x 2)");
  }
  if (nx > kMaxSide || ny > kMaxSide || nx * ny > kMaxVertices) {
    throw input_error(path + ": terrain of " + std::to_string(nx) + " x " + std::to_string(ny) +
                      " vertices exceeds the limit (" + std::to_string(kMaxSide) + " per side, " +
                      std::to_string(kMaxVertices) + " in all)");
  }
}

void check_height_range(const std::string& path, const HeightRange& range) {
  if (!(std::fabs(range.min) <= kMaxAbsHeight && std::fabs(range.max) <= kMaxAbsHeight &&
        range.max > range.min)) {
    throw input_error(path + ": height range " + format_number(range.min) + ":" +
                      format_number(range.max) + " m is not an increasing range within ±" +
                      format_number(kMaxAbsHeight) + " m");
  }
}

void check_cell_size(const std::string& path, double cell) {
  if (!(cell >= kMinCell && cell <= kMaxCell)) {
    throw input_error(path + ": cell size " + format_number(cell) + " m is outside " +
                      format_number(kMinCell) + " to " + format_number(kMaxCell) + " m");
  }
}

void check_origin(const std::string& path, double origin_x, double origin_z) {
  if (!(std::fabs(origin_x) <= kMaxAbsOrigin && std::fabs(origin_z) <= kMaxAbsOrigin))
    throw input_error(path + ": the grid's origin is not a finite coordinate within ±1e12 m");
}

void check_terrain_values(const std::string& path, const Heightmap& terrain,
                          const std::string& quantity, const std::string& unit) {
  check_cell_size(path, terrain.cell);
  check_origin(path, terrain.origin_x, terrain.origin_z);
  for (int j = 0; j < terrain.ny; ++j) {
    for (int i = 0; i < terrain.nx; ++i) {
      if (!(std::fabs(terrain.at(i, j)) <= kMaxAbsHeight)) {
        throw input_error(path + ": " + quantity + " " + format_number(terrain.at(i, j)) + unit +
                          " at column " + std::to_string(i) + ", row " + std::to_string(j) +
                          " is not a finite number within ±" + format_number(kMaxAbsHeight) + unit);
      }
    }
  }
}

void check_finite_heights(const std::string& path, const Heightmap& terrain) {
  for (int j = 0; j < terrain.ny; ++j) {
    for (int i = 0; i < terrain.nx; ++i) {
      if (!std::isfinite(terrain.at(i, j))) {
        throw input_error(path + ": height at column " + std::to_string(i) + ", row " +
                          std::to_string(j) + " is not a finite number");
      }
    }
  }
}

std::vector<float> heights_with_holes(const Heightmap& terrain, float nodata) {
  std::vector<float> h = terrain.h;
  for (std::size_t k = 0; k < h.size(); ++k)
    if (terrain.georef.hole(k)) h[k] = nodata;
  return h;
}

void apply_nodata_policy(const std::string& path, Heightmap& terrain, long long holes,
                         NodataPolicy policy) {
  if (holes == 0) return;
  if (policy == NodataPolicy::kRefuse) {
    throw input_error(path + ": " + std::to_string(holes) +
                      " NODATA cells; fill them from their neighbours with terrain.nodata = "
                      "\"fill\" (runnel convert: --nodata fill)");
  }
  terrain.georef.holes.assign(terrain.h.size(), 0);
  for (std::size_t k = 0; k < terrain.h.size(); ++k)
    terrain.georef.holes[k] = std::isnan(terrain.h[k]) ? 1 : 0;
  if (fill_holes(terrain) < 0) throw input_error(path + ": every cell is NODATA");
  std::cerr << "runnel: " << terminal_safe(path) << ": filled " << holes
            << " NODATA cells from their neighbours\n";
}

long long fill_holes(Heightmap& terrain) {
  // Grow valid data into the holes one ring per pass: each hole next to valid vertices takes the
  // mean of its valid 8-neighbours. Deterministic (a pass reads only the previous pass's values).
  long long filled = 0;
  std::vector<std::size_t> holes;
  for (std::size_t k = 0; k < terrain.h.size(); ++k) {
    if (std::isnan(terrain.h[k])) holes.push_back(k);
  }
  if (holes.size() == terrain.h.size()) return -1;
  while (!holes.empty()) {
    std::vector<std::pair<std::size_t, float>> updates;
    std::vector<std::size_t> remaining;
    for (std::size_t k : holes) {
      const int i = static_cast<int>(k % terrain.nx), j = static_cast<int>(k / terrain.nx);
      double sum = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if ((di == 0 && dj == 0) || a < 0 || b < 0 || a >= terrain.nx || b >= terrain.ny)
            continue;
          const float v = terrain.at(a, b);
          if (!std::isnan(v)) {
            sum += v;
            ++count;
          }
        }
      }
      if (count > 0)
        updates.emplace_back(k, static_cast<float>(sum / count));
      else
        remaining.push_back(k);
    }
    for (auto& [k, v] : updates) terrain.h[k] = v;
    filled += static_cast<long long>(updates.size());
    holes.swap(remaining);
  }
  return filled;
}

namespace {

// A georeferenced raster in the terrain's CRS must cover the terrain's extent, within a cell.
void check_raster_place(const std::string& path, const std::string& what, const Heightmap& r,
                        const Heightmap& terrain) {
  if (r.georef.crs_wkt.empty() || r.georef.crs_wkt != terrain.georef.crs_wkt) return;
  const double slack = std::max(r.cell, terrain.cell);
  const double r_east = r.origin_x + r.nx * r.cell, r_north = r.origin_z + r.ny * r.cell;
  const double t_east = terrain.origin_x + terrain.nx * terrain.cell;
  const double t_north = terrain.origin_z + terrain.ny * terrain.cell;
  if (std::fabs(r.origin_x - terrain.origin_x) <= slack && std::fabs(r_east - t_east) <= slack &&
      std::fabs(r.origin_z - terrain.origin_z) <= slack && std::fabs(r_north - t_north) <= slack)
    return;
  auto extent = [](double w, double s, double e, double n) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "x %.10g to %.10g, y %.10g to %.10g", w, e, s, n);
    return std::string(buf);
  };
  throw input_error(path + ": " + what + " covers " +
                    extent(r.origin_x, r.origin_z, r_east, r_north) + " but the terrain " +
                    extent(terrain.origin_x, terrain.origin_z, t_east, t_north) +
                    " (same CRS): it belongs to another place");
}

}  // namespace

std::vector<float> read_vertex_raster(const std::string& path, int nx, int ny,
                                      const std::string& what, const VertexValueCheck& check,
                                      const Heightmap* terrain) {
  ReadOptions options;
  options.quantity = what;
  options.unit = "";
  options.npy_nan_is_nodata = false;
  const Heightmap r = read_terrain(path, options);
  if (check)
    for (float v : r.h)
      if (const std::string why = check(v); !why.empty())
        throw input_error(path + ": " + what + " holds " + format_number(v) + "; " + why);
  if (terrain) check_raster_place(path, what, r, *terrain);
  if (r.nx == nx && r.ny == ny) return r.h;
  // Corner vertices map onto corner vertices: the same extent, so the same shape, within a cell of
  // the raster (a coarser raster cannot always match the terrain's aspect exactly) or 1 %.
  const double wanted = double(std::max(nx - 1, 1)) / std::max(ny - 1, 1);
  const double columns = r.nx - 1, columns_for_shape = (r.ny - 1) * wanted;
  if (std::fabs(columns - columns_for_shape) > std::max(1.0, 0.01 * columns))
    throw input_error(path + ": " + what + " has " + std::to_string(r.nx) + " x " +
                      std::to_string(r.ny) + " vertices, the terrain " + std::to_string(nx) +
                      " x " + std::to_string(ny) +
                      ": another shape, which resampling would stretch");
  std::cerr << "warning: " << what << " " << terminal_safe(path) << ": " << r.nx << " x " << r.ny
            << " vertices resampled bilinearly to the terrain's " << nx << " x " << ny << "\n";
  std::vector<float> out(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = nx > 1 ? i * double(r.nx - 1) / (nx - 1) : 0;
      const double z = ny > 1 ? j * double(r.ny - 1) / (ny - 1) : 0;
      const int i0 = std::min(static_cast<int>(x), std::max(r.nx - 2, 0));
      const int j0 = std::min(static_cast<int>(z), std::max(r.ny - 2, 0));
      const int i1 = std::min(i0 + 1, r.nx - 1), j1 = std::min(j0 + 1, r.ny - 1);
      const double u = x - i0, v = z - j0;
      out[static_cast<std::size_t>(j) * nx + i] =
          static_cast<float>((1 - u) * (1 - v) * r.at(i0, j0) + u * (1 - v) * r.at(i1, j0) +
                             (1 - u) * v * r.at(i0, j1) + u * v * r.at(i1, j1));
    }
  }
  return out;
}

}  // namespace runnel
