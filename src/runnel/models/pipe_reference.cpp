// SPDX-License-Identifier: MIT
#include "runnel/models/pipe_reference.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/rng.hpp"

namespace runnel::pipe_reference {
namespace {

constexpr int kDi[4] = {-1, 1, 0, 0}, kDj[4] = {0, 0, -1, 1};  // L R T B
double random(std::uint64_t seed, std::uint64_t stream, std::uint64_t step, std::size_t k) {
  return keyed_uniform(rng_key(seed, stream, step), static_cast<std::uint32_t>(k));
}

// What a cell with `sediment` sends through pipe d (cl/models/pipe.cl's pipe_send, which shares at
// most kPipeSendable quanta of it).
std::int64_t sent(std::int64_t held, const double* flux4, double share, double u, int d) {
  const std::int64_t sediment = std::min<std::int64_t>(held, kPipeSendable);
  double before = 0;
  for (int e = 0; e < d; ++e) before += flux4[e] * share;
  const double upto = std::min(1.0, before + flux4[d] * share);
  before = std::min(1.0, before);
  return static_cast<std::int64_t>(std::floor(static_cast<double>(sediment) * upto + u)) -
         static_cast<std::int64_t>(std::floor(static_cast<double>(sediment) * before + u));
}

}  // namespace

namespace {

bool inside(int x, int z, int nx, int ny) {
  return x >= 0 && z >= 0 && x < nx && z < ny;
}

// The virtual pipes' outflows from every cell: accelerated by the water levels' differences,
// slowed by Manning friction, scaled so no cell sends more water than it has.
std::vector<double> outflow_fluxes(const State& st, const std::vector<double>& d1, int nx, int ny,
                                   double l, double q, const PipeSettings& s, double dt) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<double> flux(4 * n);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double level = static_cast<double>(st.height[k]) * q + d1[k];
      double f[4], total = 0;
      for (int d = 0; d < 4; ++d) {
        const int x = i + kDi[d], z = j + kDj[d];
        double other = 0;
        if (inside(x, z, nx, ny)) {
          const std::size_t m = static_cast<std::size_t>(z) * nx + x;
          other = static_cast<double>(st.height[m]) * q + d1[m];
        } else if (s.closed()) {
          f[d] = 0;
          continue;
        }
        f[d] = std::max(0.0, st.flux[4 * k + d] + dt * s.area * s.gravity * (level - other) / l);
        if (s.manning_n > 0) {
          const double h = std::max(d1[k], 1e-3), v = f[d] / (l * h);
          f[d] /= 1 + dt * s.gravity * s.manning_n * s.manning_n * v / (h * std::cbrt(h));
        }
        total += f[d];
      }
      const double scale = total > 0 ? std::min(1.0, d1[k] * l * l / (total * dt)) : 0.0;
      for (int d = 0; d < 4; ++d) flux[4 * k + d] = f[d] * scale;
    }
  }
  return flux;
}

// The depths after the exchange, and the velocities from the mean flux through each cell.
void update_water(State& st, const std::vector<double>& flux, const std::vector<double>& d1, int nx,
                  int ny, double l, double dt) {
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      double in[4] = {0, 0, 0, 0}, in_total = 0, out_total = 0;
      for (int d = 0; d < 4; ++d) {
        out_total += flux[4 * k + d];
        const int x = i + kDi[d], z = j + kDj[d];
        if (!inside(x, z, nx, ny)) continue;
        in[d] = flux[4 * (static_cast<std::size_t>(z) * nx + x) + (d ^ 1)];
        in_total += in[d];
      }
      const double d2 = std::max(0.0, d1[k] + dt * (in_total - out_total) / (l * l));
      st.depth[k] = d2;
      const double wx = 0.5 * (in[0] - flux[4 * k + 0] + flux[4 * k + 1] - in[1]);
      const double wz = 0.5 * (in[2] - flux[4 * k + 2] + flux[4 * k + 3] - in[3]);
      const double mean_depth = 0.5 * (d1[k] + d2);
      st.velocity[2 * k] = mean_depth > 1e-6 ? wx / (l * mean_depth) : 0.0;
      st.velocity[2 * k + 1] = mean_depth > 1e-6 ? wz / (l * mean_depth) : 0.0;
    }
  }
}

// Erosion and deposition on the slope of the heights as the step began; evaporation.
void erode_and_evaporate(State& st, int nx, int ny, double l, double q, const PipeSettings& s,
                         double dt, std::uint64_t seed, std::uint64_t step_index) {
  const std::vector<std::int64_t> start = st.height;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, nx - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, ny - 1);
      auto h = [&](int a, int b) {
        return static_cast<double>(start[static_cast<std::size_t>(b) * nx + a]) * q;
      };
      const double gx = (h(i1, j) - h(i0, j)) / ((i1 - i0) * l);
      const double gz = (h(i, j1) - h(i, j0)) / ((j1 - j0) * l);
      const double sin_slope = std::sqrt(gx * gx + gz * gz) / std::sqrt(1 + gx * gx + gz * gz);
      const double speed = std::hypot(st.velocity[2 * k], st.velocity[2 * k + 1]);
      const double capacity =
          std::min(s.capacity * std::max(sin_slope, s.min_tilt) * speed, st.depth[k]);
      const double carried = static_cast<double>(st.sediment[k]) * q;
      const double u = random(seed, kPipeErodeStream, step_index, k);
      if (capacity > carried) {
        const auto amount = static_cast<std::int64_t>(
            std::floor(-std::expm1(-s.dissolve * dt) * (capacity - carried) / q + u));
        st.height[k] -= amount;
        st.sediment[k] += amount;
      } else {
        const auto amount = std::min(
            st.sediment[k], static_cast<std::int64_t>(std::floor(
                                -std::expm1(-s.deposit * dt) * (carried - capacity) / q + u)));
        st.height[k] += amount;
        st.sediment[k] -= amount;
      }
      st.depth[k] *= std::exp(-s.evaporation * dt);
    }
  }
}

// Upwind transport of the sediment with the water that leaves.
void transport_sediment(State& st, const std::vector<double>& d1, int nx, int ny, double l,
                        double dt, std::uint64_t seed, std::uint64_t step_index) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<std::int64_t> next(n);
  std::vector<double> share(n), u(n);
  for (std::size_t k = 0; k < n; ++k) {
    share[k] = d1[k] > 0 ? dt / (d1[k] * l * l) : 0.0;
    u[k] = random(seed, kPipeTransportStream, step_index, k);
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      std::int64_t total = st.sediment[k];
      for (int d = 0; d < 4; ++d) {
        const std::int64_t out = sent(st.sediment[k], &st.flux[4 * k], share[k], u[k], d);
        total -= out;
        const int x = i + kDi[d], z = j + kDj[d];
        if (!inside(x, z, nx, ny)) {
          st.outflow += std::max<std::int64_t>(out, 0);
          continue;
        }
        const std::size_t m = static_cast<std::size_t>(z) * nx + x;
        total += sent(st.sediment[m], &st.flux[4 * m], share[m], u[m], d ^ 1);
      }
      next[k] = total;
    }
  }
  st.sediment = next;
}

}  // namespace

void step(State& st, int nx, int ny, double l, double q, const PipeSettings& s, double dt,
          std::uint64_t seed, std::uint64_t step_index) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<double> d1(n);
  for (std::size_t k = 0; k < n; ++k) d1[k] = st.depth[k] + dt * s.rain;
  const std::vector<double> flux = outflow_fluxes(st, d1, nx, ny, l, q, s, dt);
  update_water(st, flux, d1, nx, ny, l, dt);
  st.flux = flux;
  erode_and_evaporate(st, nx, ny, l, q, s, dt, seed, step_index);
  transport_sediment(st, d1, nx, ny, l, dt, seed, step_index);
}

}  // namespace runnel::pipe_reference
