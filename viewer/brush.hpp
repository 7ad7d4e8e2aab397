// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/rain_units.hpp"
#include "runnel/models/interaction.hpp"

namespace runnel::viewer {

// The rain brush in units people know: a radius in metres and an intensity in mm/h of rain.
struct Brush {
  bool over_terrain = false;
  double x = 0, z = 0;   // m from the terrain's first vertex
  double radius = 20;    // m
  double intensity = 0;  // mm/h
  RainDisc disc() const { return {x, z, radius, rain_depth_rate(intensity)}; }
  double discharge() const {
    return rain_depth_rate(intensity) * 3.14159265358979 * radius * radius;
  }
};

// The starting brush on a terrain: a radius of about 8 % of its extent and an intensity that rains
// about 200 SPH particles (of the default spacing, half a cell) a second on it, both rounded to
// 1, 2 or 5 times a power of ten so that they read as numbers.
Brush default_brush(const Heightmap& terrain);
double round_to_nice(double value);
// 1234567.8 → "1,234,568".
std::string with_thousands(double value);

}  // namespace runnel::viewer
