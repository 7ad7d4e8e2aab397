// SPDX-License-Identifier: MIT
#include "runnel/validation/stream_power_validation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "runnel/core/rng.hpp"
#include "runnel/landscape/flow_routing.hpp"
#include "runnel/landscape/stream_power.hpp"

namespace runnel {
namespace {

double l2_change(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t k = 0; k < a.size(); ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(s);
}

void add_error(SteadyStateCheck& c, double numerical, double analytic) {
  const double e = std::fabs(numerical - analytic) / std::fabs(analytic);
  c.worst_relative = std::max(c.worst_relative, e);
  c.mean_relative += e;
  ++c.nodes;
}

}  // namespace

SteadyStateCheck stream_power_profile(double n) {
  const int nodes = 101;
  const double spacing = 300, x0 = 300, length = (nodes - 1) * spacing;
  const double k = 1e-3, m = 0.5, u = 1e-3, dt = 1e4;
  FlowRouting r;
  std::vector<double> h(nodes), x(nodes);
  r.receiver.resize(nodes);
  r.distance.assign(nodes, spacing);
  r.area.resize(nodes);
  for (int i = 0; i < nodes; ++i) {
    x[i] = length + x0 - i * spacing;  // node 0 is the outlet
    h[i] = (x[i] - (length + x0)) * 0.001;
    r.receiver[i] = i > 0 ? i - 1 : 0;
    r.area[i] = 6.69 * std::pow(x[i], 1.67);
    r.stack.push_back(i);
  }
  r.distance[0] = 0;
  const std::vector<double> kk(nodes, k);
  SteadyStateCheck c;
  for (double change = 1e300; change > 1e-9 && c.steps < 1000000; ++c.steps) {
    const std::vector<double> before = h;
    for (int i = 1; i < nodes; ++i) h[i] += u * dt;
    erode_stream_power(h, r, kk, m, n, dt);
    change = l2_change(h, before);
  }
  for (int i = 1; i < nodes; ++i) {
    const double s = (h[i] - h[i - 1]) / spacing;
    add_error(c, s, std::pow(u / k, 1 / n) * std::pow(r.area[i], -m / n));
  }
  c.mean_relative /= c.nodes;
  c.fitted_theta = fit_slope_area(h, r, 0.0).theta;
  return c;
}

SteadyStateCheck stream_power_grid(int nx, double n, int min_cells) {
  const double cell = 100, k = 2e-5, m = 0.5, u = 1e-3, dt = 5e4;
  const std::size_t size = static_cast<std::size_t>(nx) * nx;
  std::vector<double> h(size, 0.0);
  for (int j = 1; j < nx - 1; ++j)
    for (int i = 1; i < nx - 1; ++i)
      h[static_cast<std::size_t>(j) * nx + i] =
          rng_uniform_double(11, 0x5350ULL, static_cast<std::uint64_t>(j) * nx + i);
  const std::vector<double> kk(size, k);
  SteadyStateCheck c;
  D8Router router(nx, nx, cell);
  const FlowRouting* routing = nullptr;  // the router's own, valid until its next route()
  for (double change = 1e300; change > 1e-9 * nx && c.steps < 200000; ++c.steps) {
    const std::vector<double> before = h;
    for (int j = 1; j < nx - 1; ++j)
      for (int i = 1; i < nx - 1; ++i) h[static_cast<std::size_t>(j) * nx + i] += u * dt;
    routing = &router.route(h);
    erode_stream_power(h, *routing, kk, m, n, dt);
    change = l2_change(h, before);
  }
  const FlowRouting& r = *routing;
  const double min_area = min_cells * cell * cell;
  for (std::size_t q = 0; q < size; ++q) {
    if (r.receiver[q] == static_cast<std::int32_t>(q) || r.area[q] < min_area) continue;
    const double s = (h[q] - h[r.receiver[q]]) / r.distance[q];
    add_error(c, s, std::pow(u / k, 1 / n) * std::pow(r.area[q], -m / n));
  }
  c.mean_relative /= std::max(1, c.nodes);
  c.fitted_theta = fit_slope_area(h, r, min_area).theta;
  return c;
}

SteadyStateCheck hillslope_diffusion() {
  const int nx = 101, ny = 5;
  const double cell = 10, u = 1e-3, d = 1.0, dt = 2;
  std::vector<double> h(static_cast<std::size_t>(nx) * ny, 0.0);
  SteadyStateCheck c;
  for (double change = 1e300; change > 1e-12 && c.steps < 10000000; ++c.steps) {
    const std::vector<double> before = h;
    for (int j = 0; j < ny; ++j)
      for (int i = 1; i < nx - 1; ++i) h[static_cast<std::size_t>(j) * nx + i] += u * dt;
    diffuse(h, nx, ny, cell, d, dt, BaseLevel::kWestEast);
    change = l2_change(h, before);
  }
  const double divide = 0.5 * (nx - 1) * cell;
  for (int i = 1; i < nx; ++i) {
    // The slope between vertices i − 1 and i, at their midpoint, x from the divide.
    const double x = std::fabs((i - 0.5) * cell - divide);
    const double s = std::fabs(h[static_cast<std::size_t>(2) * nx + i] -
                               h[static_cast<std::size_t>(2) * nx + i - 1]) /
                     cell;
    add_error(c, s, u * x / d);
  }
  c.mean_relative /= c.nodes;
  return c;
}

JsonObject json(const SteadyStateCheck& c) {
  return JsonObject()
      .add("worst_relative_error", c.worst_relative)
      .add("mean_relative_error", c.mean_relative)
      .add("fitted_theta", c.fitted_theta)
      .add("nodes", c.nodes)
      .add("steps", c.steps);
}

}  // namespace runnel
