// SPDX-License-Identifier: MIT
#include "runnel/landscape/stream_power.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {
namespace {

// x^e, with the exponents stream-power runs use most (m = 0.5, n = 1 or 2) done without pow():
// pow() was a sixth of a step.
double power(double x, double e) {
  if (e == 1.0) return x;
  if (e == 0.5) return std::sqrt(x);
  if (e == 2.0) return x * x;
  return std::pow(x, e);
}

}  // namespace

void erode_stream_power(std::vector<double>& h, const FlowRouting& r, const std::vector<double>& k,
                        double m, double n, double dt) {
  for (const std::int32_t node : r.stack) {
    const std::int32_t rec = r.receiver[node];
    if (rec == node) continue;
    const double hr = h[rec], h0 = h[node];
    if (h0 <= hr) continue;  // in a depression, or flat: no incision
    const double f = k[node] * dt * power(r.area[node], m) / power(r.distance[node], n);
    if (n == 1.0) {
      h[node] = (h0 + f * hr) / (1.0 + f);
      continue;
    }
    // g(x) = x − (h0 − hr) + f x^n, x = h' − hr in [0, h0 − hr]: increasing, one root.
    double x = h0 - hr;
    for (int it = 0; it < 100; ++it) {
      const double g = x - (h0 - hr) + f * std::pow(x, n);
      const double dg = 1.0 + f * n * std::pow(x, n - 1.0);
      const double next = std::max(x - g / dg, 0.0);
      const bool done = std::fabs(next - x) <= 1e-12 * std::max(1.0, std::fabs(h0));
      x = next;
      if (done) break;
    }
    h[node] = hr + x;
  }
}

void deposit_sediment_flux(std::vector<double>& h, const std::vector<double>& before,
                           const FlowRouting& r, double g, double cell_area) {
  // Volumes over the step (m³), not rates: Qs·dt. Donors before receivers: up the stack.
  std::vector<double> load(h.size(), 0.0);
  for (std::size_t s = r.stack.size(); s-- > 0;) {
    const std::int32_t k = r.stack[s];
    const double eroded = (before[k] - h[k]) * cell_area;
    const double arriving = load[k];
    const double deposited = std::min(arriving, g * arriving * cell_area / r.area[k]);
    h[k] += deposited / cell_area;
    const double leaving = arriving - deposited + eroded;
    if (r.receiver[k] != k) load[r.receiver[k]] += leaving;
  }
}

SlopeArea fit_slope_area(const std::vector<double>& h, const FlowRouting& r, double min_area) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  SlopeArea f;
  for (std::size_t k = 0; k < h.size(); ++k) {
    const std::int32_t rec = r.receiver[k];
    if (rec == static_cast<std::int32_t>(k) || r.area[k] < min_area) continue;
    const double s = (h[k] - h[rec]) / r.distance[k];
    if (!(s > 0)) continue;
    const double x = std::log(r.area[k]), y = std::log(s);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    ++f.nodes;
  }
  if (f.nodes < 2) return f;
  const double n = f.nodes, slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  f.theta = -slope;
  f.ks = std::exp((sy - slope * sx) / n);
  return f;
}

void diffuse(std::vector<double>& h, int nx, int ny, double cell, double d, double dt,
             BaseLevel base) {
  if (d <= 0 || dt <= 0) return;
  const int substeps = static_cast<int>(std::ceil(dt * 4.1 * d / (cell * cell)));
  const double tau = dt / substeps, c = d * tau / (cell * cell);
  std::vector<double> next(h);
  for (int s = 0; s < substeps; ++s) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (is_base_level(i, j, nx, ny, base)) continue;
        const std::size_t q = static_cast<std::size_t>(j) * nx + i;
        // A closed edge mirrors its row: no flux across it.
        const double north = j > 0 ? h[q - nx] : h[q], south = j < ny - 1 ? h[q + nx] : h[q];
        next[q] = h[q] + c * (h[q - 1] + h[q + 1] + north + south - 4 * h[q]);
      }
    h.swap(next);
  }
}

}  // namespace runnel
