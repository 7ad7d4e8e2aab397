// SPDX-License-Identifier: MIT
#include "runnel/sph/rain_reference.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/rng.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel::rain_reference {
namespace {
constexpr std::uint64_t kRainStream = 0x7261696eULL;  // "rain", as cl/rain.cl

// The depth at (x, z), bilinear in its cell of the vertices' depths (0 where none are given).
double depth_at(const std::vector<double>& depth, const Heightmap& t, double x, double z) {
  if (depth.empty()) return 0.0;
  const double u = x / t.cell, v = z / t.cell;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, t.nx - 2);
  const int j = std::clamp(static_cast<int>(std::floor(v)), 0, t.ny - 2);
  const double fu = std::clamp(u - i, 0.0, 1.0), fv = std::clamp(v - j, 0.0, 1.0);
  auto at = [&](int a, int b) { return depth[static_cast<std::size_t>(b) * t.nx + a]; };
  return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) +
         fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
}
}  // namespace

std::vector<Drop> emit(const RainSettings& r, double contact_radius, double surface_eps,
                       const Heightmap& terrain, std::uint64_t seed, std::uint64_t first_counter,
                       std::size_t count, double spread, double gravity,
                       const std::vector<double>& water_depth) {
  const Heightmap contact = contact_surface(terrain, contact_radius);
  const double lx = (terrain.nx - 1) * terrain.cell, lz = (terrain.ny - 1) * terrain.cell;
  std::vector<Drop> drops;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t counter = 4 * (first_counter + k);
    const double u1 = rng_uniform(seed, kRainStream, counter);
    const double u2 = rng_uniform(seed, kRainStream, counter + 1);
    const double u3 = rng_uniform(seed, kRainStream, counter + 2);
    double x, z;
    if (r.region == RainSettings::Region::kDisc) {  // uniform in the disc: radius ∝ sqrt(u)
      const double radius = r.b * std::sqrt(u1), theta = 2 * M_PI * u2;
      x = r.a + radius * std::cos(theta);
      z = r.c + radius * std::sin(theta);
    } else if (r.region == RainSettings::Region::kRectangle) {
      x = r.a + (r.b - r.a) * u1;
      z = r.c + (r.d - r.c) * u2;
    } else {
      x = lx * u1;
      z = lz * u2;
    }
    x = std::clamp(x, 0.0, lx);
    z = std::clamp(z, 0.0, lz);
    const double tau = spread * (static_cast<double>(count - k) - 0.5) / static_cast<double>(count);
    const double base = surface_height(terrain, x, z) +
                        (r.above_water ? depth_at(water_depth, terrain, x, z) : 0.0);
    const double y = std::max(base + r.spawn_height - tau * (r.speed + 0.5 * gravity * tau),
                              surface_height(contact, x, z) + surface_eps);
    drops.push_back({x, y, z, r.lifespan * (1 + r.lifespan_jitter * (2 * u3 - 1)),
                     -r.speed - gravity * tau, tau});
  }
  return drops;
}

}  // namespace runnel::rain_reference
