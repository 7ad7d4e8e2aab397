// SPDX-License-Identifier: MIT
#include "runnel/terrain/thermal_reference.hpp"

#include <algorithm>
#include <cmath>

namespace runnel::thermal_reference {
namespace {
constexpr int kDi[4] = {-1, 1, 0, 0}, kDj[4] = {0, 0, -1, 1};
}

std::vector<std::int64_t> relax(const std::vector<std::int64_t>& height, int nx, int ny,
                                std::int64_t talus, double rate, bool height_aware,
                                double hardness) {
  const auto [lo, hi] = std::minmax_element(height.begin(), height.end());
  const double h_min = static_cast<double>(*lo), h_range = static_cast<double>(*hi - *lo);
  std::vector<std::int64_t> outflow(4 * height.size(), 0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double h = static_cast<double>(height[k]);
      double threshold = static_cast<double>(talus);
      if (height_aware && h_range > 0) {
        threshold = std::trunc(threshold * (1.0 + hardness * (h - h_min) / h_range));
      }
      double excess[4] = {0, 0, 0, 0}, excess_sum = 0, d_max = 0;
      for (int d = 0; d < 4; ++d) {
        const int a = i + kDi[d], b = j + kDj[d];
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        const double diff = h - static_cast<double>(height[static_cast<std::size_t>(b) * nx + a]);
        if (diff > threshold) {
          excess[d] = diff - threshold;
          excess_sum += excess[d];
          d_max = std::max(d_max, diff);
        }
      }
      if (excess_sum <= 0) continue;
      const double total = std::floor(rate * (d_max - threshold));
      for (int d = 0; d < 4; ++d) {
        outflow[4 * k + d] = static_cast<std::int64_t>(std::floor(total * excess[d] / excess_sum));
      }
    }
  }
  std::vector<std::int64_t> after = height;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      for (int d = 0; d < 4; ++d) {
        after[k] -= outflow[4 * k + d];
        const int a = i + kDi[d], b = j + kDj[d];
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        after[k] += outflow[4 * (static_cast<std::size_t>(b) * nx + a) + (d ^ 1)];
      }
    }
  }
  return after;
}

}  // namespace runnel::thermal_reference
