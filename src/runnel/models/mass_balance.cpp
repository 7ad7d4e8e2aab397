// SPDX-License-Identifier: MIT
#include "runnel/models/mass_balance.hpp"

#include <cmath>

namespace runnel {

JsonObject MassBalance::json() const {
  return JsonObject()
      .add("terrain_change", terrain_change)
      .add("suspended", suspended)
      .add("outflow", outflow)
      .add("lost", lost)
      .add("uplift", uplift)
      .add("imposed", imposed)
      .add("residual", residual)
      .add("residual_quanta", residual_quanta)
      .add("eroded", eroded)
      .add("deposited", deposited)
      .add("relative", relative);
}

MassBalance mass_balance_of(const std::vector<std::int64_t>& initial,
                            const std::vector<std::int64_t>& current, long long suspended,
                            long long outflow, long long lost, double q, long long uplift,
                            const std::vector<std::int64_t>& uplift_per_vertex,
                            const ImposedChange& imposed) {
  const std::vector<std::int64_t>& imposed_per_vertex = imposed.per_vertex();
  long long change = 0, eroded = 0, deposited = 0;
  for (std::size_t k = 0; k < current.size(); ++k) {
    long long d = current[k] - initial[k];
    change += d;
    if (!uplift_per_vertex.empty()) d -= uplift_per_vertex[k];
    if (!imposed_per_vertex.empty()) d -= imposed_per_vertex[k];
    if (d < 0)
      eroded -= d;
    else
      deposited += d;
  }
  MassBalance m;
  m.residual_quanta = change + suspended + outflow + lost - uplift - imposed.total();
  m.uplift = uplift * q;
  m.imposed = static_cast<double>(imposed.total()) * q;
  m.terrain_change = change * q;
  m.suspended = suspended * q;
  m.outflow = outflow * q;
  m.lost = lost * q;
  m.residual = m.residual_quanta * q;
  m.eroded = eroded * q;
  m.deposited = deposited * q;
  m.relative = eroded > 0 ? std::fabs(static_cast<double>(m.residual_quanta)) / eroded : 0.0;
  return m;
}

}  // namespace runnel
