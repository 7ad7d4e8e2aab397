// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace runnel {

// Where a heightmap lies on the Earth, as a georeferenced source gave it (docs/terrain-formats.md):
// its coordinate reference system and the value that marked missing data there. Carried through
// runs, comparisons and checkpoints to every raster written.
struct Georeference {
  std::string crs_wkt;           // OGC WKT; empty: not georeferenced
  std::optional<double> nodata;  // the source's NODATA value, written back as the rasters' own
  // 1 where the source had NODATA (nx × ny, row-major; empty: no holes). The holes are filled so
  // a model can run over them, and written back as NODATA in every raster with a NODATA value
  // (GeoTIFF, ASC); the metrics leave them out (docs/terrain-formats.md).
  std::vector<std::uint8_t> holes;
  bool hole(std::size_t k) const { return !holes.empty() && holes[k] != 0; }
  bool operator==(const Georeference&) const = default;
};

// A terrain heightmap: nx × ny vertices, spacing `cell` metres, heights in metres.
// Vertex (i, j) sits at world (i·cell, h, j·cell): x east, z south (grid rows), y up.
// Storage is row-major with i fastest: h[j·nx + i].
struct Heightmap {
  int nx = 0;
  int ny = 0;
  double cell = 1.0;  // m
  // The grid's lower-left corner in the source's coordinates (ESRI ASCII's xllcorner/yllcorner;
  // GeoTIFF's top-left corner is (origin_x, origin_z + ny·cell)). Row 0 is the northern row.
  double origin_x = 0.0;  // m
  double origin_z = 0.0;  // m
  Georeference georef;
  std::vector<float> h;  // m
  // The heights as a caller gave them in double precision (Python's float64 arrays, a Landlab
  // grid), or empty. A model's fixed-point heights are made from these, so a float64 terrain is
  // exact to the quantum; a vertex whose float height no longer is this value rounded (edited
  // since, filled as a hole) takes its float height.
  std::vector<double> exact;  // m

  Heightmap() = default;
  Heightmap(int nx_, int ny_, double cell_, float fill = 0.0f)
      : nx(nx_), ny(ny_), cell(cell_), h(static_cast<std::size_t>(nx_) * ny_, fill) {}

  std::size_t size() const { return h.size(); }
  float& at(int i, int j) { return h[static_cast<std::size_t>(j) * nx + i]; }
  float at(int i, int j) const { return h[static_cast<std::size_t>(j) * nx + i]; }

  // The height a model starts vertex k at: the exact height where the float one still is it.
  double start_height(std::size_t k) const {
    return exact.size() == h.size() && static_cast<float>(exact[k]) == h[k] ? exact[k] : h[k];
  }
  float min_height() const;
  float max_height() const;
  // V_terrain = cell² · Σ_v h_v (physics.md §1): the one definition of terrain volume, in m³.
  double volume() const;
};

// The map frame every exported geometry uses, so ParaView, a GIS and splashsurf see one scene:
// X east and Y north in the terrain's coordinates (its CRS when it has one), Z up. runnel's world
// frame has x east from the first column, z south from the northern row, y up. A vertex stands
// at its pixel's centre, as GDAL, QGIS and Landlab place a raster's values: column 0 half a cell
// east of the raster's western edge (origin_x), row 0 half a cell south of its northern edge.
struct MapFrame {
  double west = 0, north = 0;  // map X of column 0, map Y of row 0 (the northern row)
  explicit MapFrame(const Heightmap& t)
      : west(t.origin_x + 0.5 * t.cell), north(t.origin_z + (t.ny - 0.5) * t.cell) {}
  double x(double world_x) const { return west + world_x; }
  double y(double world_z) const { return north - world_z; }
  double world_x(double map_x) const { return map_x - west; }
  double world_z(double map_y) const { return north - map_y; }
};

// after − before per vertex (m; negative where the terrain was eroded, positive where deposited),
// on the grid and georeferencing of `before`.
Heightmap height_change(const Heightmap& before, const Heightmap& after);

// Every `factor`-th vertex in each direction (the cell grows by `factor`): a preview of a large
// terrain for pictures.
Heightmap subsample(const Heightmap& t, int factor);

// Hard limits on the size of a terrain, so a corrupt header cannot make us allocate terabytes.
inline constexpr int kMaxSide = 32768;                // vertices per side
inline constexpr long long kMaxVertices = 1LL << 28;  // 268,435,456 vertices (1 GiB of floats)

}  // namespace runnel
