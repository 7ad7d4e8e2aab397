// SPDX-License-Identifier: MIT
#include "runnel/models/droplet_reference.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/rng.hpp"

namespace runnel::droplet_reference {
namespace {

constexpr std::uint64_t kDropletStream = 0x64726f70ULL;  // "drop"

struct Droplet {
  double x, z, dir_x = 0, dir_z = 0, speed, water;
  std::int64_t load = 0;
  bool done = false;
};

// Bilinear height (m) and gradient at (x, z) in cell units.
double height_at(const std::vector<double>& h, int nx, double x, double z, double& gx, double& gz) {
  const int i = static_cast<int>(x), j = static_cast<int>(z);
  const double u = x - i, v = z - j;
  const std::size_t k = static_cast<std::size_t>(j) * nx + i;
  const double h00 = h[k], h10 = h[k + 1], h01 = h[k + nx], h11 = h[k + nx + 1];
  gx = (h10 - h00) * (1 - v) + (h11 - h01) * v;
  gz = (h01 - h00) * (1 - u) + (h11 - h10) * u;
  return h00 * (1 - u) * (1 - v) + h10 * u * (1 - v) + h01 * (1 - u) * v + h11 * u * v;
}

void deposit_bilinear(std::vector<std::int64_t>& delta, int nx, double x, double z,
                      std::int64_t quanta) {
  if (quanta <= 0) return;
  const int i = static_cast<int>(x), j = static_cast<int>(z);
  const double u = x - i, v = z - j;
  const double w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
  const std::size_t k[4] = {
      static_cast<std::size_t>(j) * nx + i, static_cast<std::size_t>(j) * nx + i + 1,
      static_cast<std::size_t>(j + 1) * nx + i, static_cast<std::size_t>(j + 1) * nx + i + 1};
  std::int64_t given = 0;
  int largest = 0;
  for (int c = 0; c < 4; ++c) {
    const std::int64_t part = std::min(
        static_cast<std::int64_t>(std::floor(static_cast<double>(quanta) * w[c])), quanta - given);
    given += part;
    if (w[c] > w[largest]) largest = c;
    delta[k[c]] += std::max<std::int64_t>(part, 0);
  }
  delta[k[largest]] += std::max<std::int64_t>(quanta - given, 0);
}

void erode_brush(std::vector<std::int64_t>& delta, int nx, int ny, double radius, double x,
                 double z, std::int64_t quanta) {
  if (quanta <= 0) return;
  const int r = static_cast<int>(std::ceil(radius));
  const int ci = static_cast<int>(x), cj = static_cast<int>(z);
  std::vector<std::pair<std::size_t, double>> weights;
  double total = 0;
  for (int dj = -r; dj <= r + 1; ++dj) {
    for (int di = -r; di <= r + 1; ++di) {
      const int a = ci + di, b = cj + dj;
      if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
      const double w = std::max(0.0, radius - std::hypot(a - x, b - z));
      if (w <= 0) continue;
      weights.emplace_back(static_cast<std::size_t>(b) * nx + a, w);
      total += w;
    }
  }
  if (total <= 0) return;
  std::int64_t taken = 0, best_part = -1;
  std::size_t best = 0;
  for (const auto& [m, w] : weights) {
    const std::int64_t part =
        std::min(static_cast<std::int64_t>(std::floor(static_cast<double>(quanta) * w / total)),
                 quanta - taken);
    taken += part;
    if (part > best_part) best_part = part, best = m;
    if (part > 0) delta[m] -= part;
  }
  if (quanta - taken > 0) delta[best] -= quanta - taken;
}

}  // namespace

std::int64_t batch(std::vector<std::int64_t>& height, int nx, int ny, double q,
                   const DropletSettings& s, std::uint64_t seed, std::uint64_t first_droplet,
                   std::size_t count) {
  std::vector<Droplet> drops(count);
  for (std::size_t d = 0; d < count; ++d) {
    const std::uint64_t id = first_droplet + d;
    const float fx = rng_uniform(seed, kDropletStream, 2 * id) * static_cast<float>(nx - 1);
    const float fz = rng_uniform(seed, kDropletStream, 2 * id + 1) * static_cast<float>(ny - 1);
    drops[d].x = std::min<double>(fx, nx - 1 - 1e-3);
    drops[d].z = std::min<double>(fz, ny - 1 - 1e-3);
    drops[d].speed = s.initial_speed;
    drops[d].water = s.initial_water;
  }
  std::int64_t outflow = 0;
  for (int step = 0; step < s.lifetime; ++step) {
    std::vector<double> metres(height.size());
    for (std::size_t k = 0; k < height.size(); ++k) metres[k] = static_cast<double>(height[k]) * q;
    std::vector<std::int64_t> delta(height.size(), 0);
    for (Droplet& p : drops) {
      if (p.done) continue;
      double gx, gz;
      const double h_old = height_at(metres, nx, p.x, p.z, gx, gz);
      double dir_x = p.dir_x * s.inertia - gx * (1 - s.inertia);
      double dir_z = p.dir_z * s.inertia - gz * (1 - s.inertia);
      const double len = std::hypot(dir_x, dir_z);
      if (len == 0) {
        deposit_bilinear(delta, nx, p.x, p.z, p.load);
        p.load = 0, p.done = true;
        continue;
      }
      dir_x /= len, dir_z /= len;
      const double x = p.x + dir_x, z = p.z + dir_z;
      if (x < 0 || z < 0 || x >= nx - 1 || z >= ny - 1) {
        outflow += p.load;
        p.load = 0, p.done = true;
        continue;
      }
      double gx2, gz2;
      const double dh = height_at(metres, nx, x, z, gx2, gz2) - h_old;
      const double capacity = std::max(-dh * p.speed * p.water * s.capacity, s.min_capacity);
      const double carried = static_cast<double>(p.load) * q;
      if (dh > 0 || carried > capacity) {
        const double amount = dh > 0 ? std::min(dh, carried) : (carried - capacity) * s.deposit;
        const std::int64_t n = std::min(p.load, static_cast<std::int64_t>(std::floor(amount / q)));
        deposit_bilinear(delta, nx, p.x, p.z, n);
        p.load -= n;
      } else {
        const double amount = std::min((capacity - carried) * s.erode, -dh);
        const auto n = static_cast<std::int64_t>(std::floor(amount / q));
        erode_brush(delta, nx, ny, s.radius, p.x, p.z, n);
        p.load += n;
      }
      p.speed = std::sqrt(std::max(0.0, p.speed * p.speed - dh * s.gravity));
      p.water *= 1 - s.evaporate;
      p.x = x, p.z = z, p.dir_x = dir_x, p.dir_z = dir_z;
      if (step == s.lifetime - 1) {
        deposit_bilinear(delta, nx, x, z, p.load);
        p.load = 0, p.done = true;
      }
    }
    for (std::size_t k = 0; k < height.size(); ++k) height[k] += delta[k];
  }
  return outflow;
}

}  // namespace runnel::droplet_reference
