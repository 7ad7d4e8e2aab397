// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/landscape/flow_routing.hpp"

namespace runnel {

// Detachment-limited stream-power incision, E = K·A^m·S^n, solved implicitly over one step dt in
// the stack's order (Braun & Willett 2013): each node's new height follows from its receiver's new
// one,
//   h' + K dt A^m ((h' − h'_r)/L)^n = h,
// exactly for n = 1, by Newton's method for n ≠ 1 (from h'_r, where the function is monotone, to
// 1e-12 of the height), unconditionally stable. Only slopes towards the receiver erode (a node at
// or below its receiver, in a depression, does not). `k` per node (uplift and erodibility maps).
// Returns the heights lowered in place; base-level nodes do not change.
void erode_stream_power(std::vector<double>& height, const FlowRouting& routing,
                        const std::vector<double>& k, double m, double n, double dt);

// The erosion–deposition form (Davy & Lague 2009, ξ–q): the material the incision of this step
// removed (`before` − `height`) travels down the stack as a sediment flux Qs (m³/yr), and each node
// takes back G·Qs/A of it (m/yr, never more than what arrives), visited donors first. Explicit in
// the flux: a deposition step of what the incision computed implicitly. `cell_area` m² per node.
void deposit_sediment_flux(std::vector<double>& height, const std::vector<double>& before,
                           const FlowRouting& routing, double g, double cell_area);

// The channels' slope–area relation S = k_s·A^−θ, least squares in log–log over the nodes draining
// at least `min_area` m² with a positive slope to their receiver.
struct SlopeArea {
  double theta = 0, ks = 0;
  int nodes = 0;
};
SlopeArea fit_slope_area(const std::vector<double>& height, const FlowRouting& routing,
                         double min_area);

// Linear hillslope diffusion ∂h/∂t = D∇²h over dt, explicit in sub-steps of at most cell²/(4.1 D)
// (stable), with the base-level edges held fixed (what diffuses into them leaves the map) and
// closed edges without flux across them.
void diffuse(std::vector<double>& height, int nx, int ny, double cell, double diffusivity,
             double dt, BaseLevel base = BaseLevel::kAllEdges);

}  // namespace runnel
