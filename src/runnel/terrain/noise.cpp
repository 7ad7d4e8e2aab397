// SPDX-License-Identifier: MIT
#include "runnel/terrain/noise.hpp"

#include <cmath>

#include "runnel/core/rng.hpp"

namespace runnel {
namespace {

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}  // quintic: C2 continuous

double lattice_dot(std::int64_t ix, std::int64_t iy, double dx, double dy, std::uint64_t seed,
                   std::uint64_t octave) {
  const std::uint64_t cell =
      (static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
  const double angle = 2.0 * M_PI * rng_uniform_double(seed, 0x6e6f697365ULL + octave, cell);
  return std::cos(angle) * dx + std::sin(angle) * dy;
}

}  // namespace

double gradient_noise(double x, double y, std::uint64_t seed, std::uint64_t octave) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const double dx = x - fx, dy = y - fy;
  const double n00 = lattice_dot(ix, iy, dx, dy, seed, octave);
  const double n10 = lattice_dot(ix + 1, iy, dx - 1, dy, seed, octave);
  const double n01 = lattice_dot(ix, iy + 1, dx, dy - 1, seed, octave);
  const double n11 = lattice_dot(ix + 1, iy + 1, dx - 1, dy - 1, seed, octave);
  const double u = fade(dx), v = fade(dy);
  return (n00 * (1 - u) + n10 * u) * (1 - v) + (n01 * (1 - u) + n11 * u) * v;
}

}  // namespace runnel
