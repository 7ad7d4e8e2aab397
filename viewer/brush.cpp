// SPDX-License-Identifier: MIT
#include "brush.hpp"

#include <algorithm>
#include <cmath>
#include "runnel/core/rain_units.hpp"

namespace runnel::viewer {

double round_to_nice(double value) {
  if (!(value > 0)) return value;
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  const double m = value / decade;
  return decade * (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0);
}

Brush default_brush(const Heightmap& t) {
  Brush b;
  const double extent = std::max(t.nx - 1, t.ny - 1) * t.cell;
  b.radius = round_to_nice(0.08 * extent);
  const double spacing = 0.5 * t.cell, area = M_PI * b.radius * b.radius;
  b.intensity = round_to_nice(rain_intensity(200.0 * spacing * spacing * spacing / area));
  return b;
}

std::string with_thousands(double value) {
  const long long v = std::llround(std::fabs(value));
  std::string digits = std::to_string(v), out;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return (value < 0 && v != 0 ? "-" : "") + out;
}

}  // namespace runnel::viewer
