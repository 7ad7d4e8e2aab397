// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/io/json.hpp"
#include "runnel/models/imposed_change.hpp"

namespace runnel {

// The terms of the mass balance (physics.md §4, models.md "Metrics"), in m³:
//   residual = ΔV_terrain + V_suspended + V_outflow + V_lost − V_uplift − V_imposed, which must be
//   0 (uplift: the stream-power model's tectonic uplift, 0 for the others).
// All terms are exact integer counts of the volume quantum, so the residual is exactly 0 unless
// something leaks; `lost` is non-zero only with a documented non-conserving option (SPH
// erosion.deposit_fraction < 1), and is then reported as its own term.
struct MassBalance {
  double terrain_change = 0, suspended = 0, outflow = 0, lost = 0, uplift = 0, residual = 0;
  // What a coupler set from outside (Model::set_elevation), an external source like the uplift.
  double imposed = 0;
  double eroded = 0, deposited = 0;  // cell²·Σmax(0, h0 − h), cell²·Σmax(0, h − h0)
  double relative = 0;               // |residual| / eroded (0 when nothing eroded)
  long long residual_quanta = 0;
  JsonObject json() const;
};

// The balance of a fixed-point terrain against its initial state, with the other terms in
// quanta; `volume_quantum` is m³ per quantum (height quantum · cell²). With tectonic uplift
// (`uplift` in all, `uplift_per_vertex` quanta each, or empty), eroded and deposited are measured
// from the uplifted initial surface: what the surface processes did, not the rock's rise. Heights
// a coupler imposed (`imposed`) are an external source the same way.
MassBalance mass_balance_of(const std::vector<std::int64_t>& initial,
                            const std::vector<std::int64_t>& current, long long suspended,
                            long long outflow, long long lost, double volume_quantum,
                            long long uplift = 0,
                            const std::vector<std::int64_t>& uplift_per_vertex = {},
                            const ImposedChange& imposed = {});

}  // namespace runnel
