// SPDX-License-Identifier: MIT
#include "runnel/terrain/standing_water.hpp"
#include "runnel/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

namespace {

using T = ParamType;

const std::vector<ParamSpec>& body_keys() {
  static const std::vector<ParamSpec> keys = {
      // clang-format off
      {"x0", T::kReal, "0", "m", -1e12, 1e12, {}, "west edge of the rectangle (map x, the terrain's georeferencing: its lower-left corner is terrain origin_x)"},
      {"x1", T::kReal, "0", "m", -1e12, 1e12, {}, "east edge (map x)"},
      {"y0", T::kReal, "0", "m", -1e12, 1e12, {}, "south edge (map y)"},
      {"y1", T::kReal, "0", "m", -1e12, 1e12, {}, "north edge (map y)"},
      {"level", T::kReal, "0", "m", -1e7, 1e7, {}, "the water surface's elevation: vertices inside the rectangle below it start under level − height of water"},
      // clang-format on
  };
  return keys;
}

void fill_body(const EntryValues& body, std::size_t index, const Heightmap& terrain,
               std::vector<float>& depth) {
  const std::string where = "water.bodies[" + std::to_string(index + 1) + "]";
  const double x0 = entry_real(body, "x0"), x1 = entry_real(body, "x1");
  const double y0 = entry_real(body, "y0"), y1 = entry_real(body, "y1");
  const double level = entry_real(body, "level");
  if (!(x1 > x0) || !(y1 > y0))
    throw input_error(where + ": the rectangle needs x0 < x1 and y0 < y1 (map metres)");
  const MapFrame map(terrain);
  long long inside = 0, wet = 0;
  for (int j = 0; j < terrain.ny; ++j)
    for (int i = 0; i < terrain.nx; ++i) {
      const double x = map.x(i * terrain.cell), y = map.y(j * terrain.cell);
      if (x < x0 || x > x1 || y < y0 || y > y1) continue;
      ++inside;
      const double d = level - terrain.at(i, j);
      if (d <= 0) continue;
      ++wet;
      float& cell = depth[static_cast<std::size_t>(j) * terrain.nx + i];
      cell = std::max(cell, static_cast<float>(d));
    }
  if (inside == 0)
    throw input_error(where + ": the rectangle [" + format_number(x0) + ", " + format_number(x1) +
                      "] x [" + format_number(y0) + ", " + format_number(y1) +
                      "] holds no vertex of the terrain (map metres)");
  if (wet == 0)
    throw input_error(where + ".level: " + format_number(level) +
                      " m is below every vertex inside the rectangle");
}

}  // namespace

std::vector<ParamSpec> water_parameters() {
  return {
      // clang-format off
      {"water.depth", T::kString, "\"\"", "", 0, 0, {}, "a raster of the water depth (m) on the terrain's vertices at t = 0 (any terrain format, relative to the scenario); empty: none"},
      {"water.bodies", T::kEntries, "[]", "", 0, 0, {}, "standing water at t = 0: [[water.bodies]] rectangles filled up to a level (a reservoir, a lake); every model with water starts with it, reported as initial_water_volume", &body_keys()},
      // clang-format on
  };
}

bool has_standing_water(const Parameters& params) {
  return !params.text("water.depth").empty() || !params.entries("water.bodies").empty();
}

std::vector<float> initial_water_depth(const Parameters& params, const Heightmap& terrain) {
  std::vector<float> depth(terrain.size(), 0.0f);
  const std::string& path = params.text("water.depth");
  if (!path.empty()) {
    depth = read_vertex_raster(
        path, terrain.nx, terrain.ny, "water.depth",
        [](float d) { return d >= 0.0f ? "" : "a depth is a finite number of metres, 0 or more"; },
        &terrain);
  }
  const auto& bodies = params.entries("water.bodies");
  for (std::size_t b = 0; b < bodies.size(); ++b) fill_body(bodies[b], b, terrain, depth);
  return depth;
}

double water_volume(const std::vector<float>& depth, const Heightmap& terrain) {
  double sum = 0;
  for (float d : depth) sum += d;
  return sum * terrain.cell * terrain.cell;
}

}  // namespace runnel
