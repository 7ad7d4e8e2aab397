// SPDX-License-Identifier: MIT
#include "runnel/models/olsen_reference.hpp"

#include <algorithm>
#include <cmath>

namespace runnel::olsen_reference {
namespace {
constexpr int kDi[4] = {-1, 1, 0, 0}, kDj[4] = {0, 0, -1, 1};
}

void iterate(State& st, int nx, int ny, const OlsenSettings& s, double q) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  for (std::size_t k = 0; k < n; ++k) {  // dissolve
    st.water[k] += s.rain;
    const auto m = static_cast<std::int64_t>(std::floor(s.solubility * st.water[k] / q));
    st.height[k] -= m;
    st.sediment[k] += m;
  }
  std::vector<double> out_water(4 * n, 0.0);
  std::vector<std::int64_t> out_sediment(4 * n, 0);
  for (int j = 0; j < ny; ++j) {  // outflow
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double w = st.water[k], a = static_cast<double>(st.height[k]) * q + w;
      double drop[4] = {0, 0, 0, 0}, total = 0, sum_lower = a;
      int lower = 1;
      for (int d = 0; d < 4; ++d) {
        const int x = i + kDi[d], z = j + kDj[d];
        if (x < 0 || z < 0 || x >= nx || z >= ny) continue;
        const std::size_t m = static_cast<std::size_t>(z) * nx + x;
        const double an = static_cast<double>(st.height[m]) * q + st.water[m];
        if (an < a) {
          drop[d] = a - an;
          total += drop[d];
          sum_lower += an;
          ++lower;
        }
      }
      const double moved = total > 0 ? std::min(w, a - sum_lower / lower) : 0.0;
      std::int64_t given = 0;
      const std::int64_t sendable = std::min<std::int64_t>(st.sediment[k], kOlsenSendable);
      for (int d = 0; d < 4; ++d) {
        const double share = total > 0 ? moved * drop[d] / total : 0.0;
        out_water[4 * k + d] = share;
        std::int64_t sent = 0;
        if (w > 0 && share > 0) {
          sent = std::min(
              static_cast<std::int64_t>(std::floor(static_cast<double>(sendable) * share / w)),
              sendable - given);
        }
        out_sediment[4 * k + d] = sent;
        given += sent;
      }
    }
  }
  std::vector<double> water = st.water;
  std::vector<std::int64_t> sediment = st.sediment;
  for (int j = 0; j < ny; ++j) {  // gather
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      for (int d = 0; d < 4; ++d) {
        water[k] -= out_water[4 * k + d];
        sediment[k] -= out_sediment[4 * k + d];
        const int x = i + kDi[d], z = j + kDj[d];
        if (x < 0 || z < 0 || x >= nx || z >= ny) continue;
        const std::size_t m = static_cast<std::size_t>(z) * nx + x;
        water[k] += out_water[4 * m + (d ^ 1)];
        sediment[k] += out_sediment[4 * m + (d ^ 1)];
      }
      water[k] = std::max(water[k], 0.0);
    }
  }
  st.water = std::move(water);
  st.sediment = std::move(sediment);
  for (std::size_t k = 0; k < n; ++k) {  // settle
    st.water[k] *= 1.0 - s.evaporation;
    const auto capacity = static_cast<std::int64_t>(std::floor(s.capacity * st.water[k] / q));
    const std::int64_t excess = st.sediment[k] - capacity;
    if (excess > 0) {
      st.height[k] += excess;
      st.sediment[k] -= excess;
    }
  }
}

}  // namespace runnel::olsen_reference
