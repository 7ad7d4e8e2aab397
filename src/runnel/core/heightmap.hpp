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

  Heightmap() = default;
  Heightmap(int nx_, int ny_, double cell_, float fill = 0.0f)
      : nx(nx_), ny(ny_), cell(cell_), h(static_cast<std::size_t>(nx_) * ny_, fill) {}

  std::size_t size() const { return h.size(); }
  float& at(int i, int j) { return h[static_cast<std::size_t>(j) * nx + i]; }
  float at(int i, int j) const { return h[static_cast<std::size_t>(j) * nx + i]; }

  float min_height() const;
  float max_height() const;
  // V_terrain = cell² · Σ_v h_v (physics.md §1): the one definition of terrain volume, in m³.
  double volume() const;
};

// The map frame every exported geometry uses, so ParaView, a GIS and splashsurf see one scene:
// X east and Y north in the terrain's coordinates (its CRS when it has one), Z up. runnel's world
// frame has x east from the first column, z south from the northern row, y up.
struct MapFrame {
  double origin_x = 0, north_edge = 0;  // map X of column 0, map Y of row 0 (the northern row)
  explicit MapFrame(const Heightmap& t)
      : origin_x(t.origin_x), north_edge(t.origin_z + (t.ny - 1) * t.cell) {}
  double x(double world_x) const { return origin_x + world_x; }
  double y(double world_z) const { return north_edge - world_z; }
  double world_x(double map_x) const { return map_x - origin_x; }
  double world_z(double map_y) const { return north_edge - map_y; }
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
