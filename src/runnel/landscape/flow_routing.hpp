// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

namespace runnel {

// Single-direction flow on a regular grid (D8, O'Callaghan & Mark 1984) in the order Braun &
// Willett 2013 use: each node drains to one receiver (itself at base level), the stack lists every
// node after its receiver, so a pass down the stack visits receivers first and a pass up it donors
// first.
struct FlowRouting {
  std::vector<std::int32_t> receiver;  // node index; a base-level node is its own receiver
  std::vector<double> distance;        // m to the receiver (0 at base level)
  std::vector<std::int32_t> stack;     // base level first, every node after its receiver
  std::vector<double> area;            // drainage area, m² (the node's own cell included)
};

// Which edges are base level (open): all four, or only the west and east ones (the north and south
// edges then close, no flow across them: a landscape that is the same in every row, as in 1-D
// tests).
enum class BaseLevel { kAllEdges, kWestEast };
// Whether vertex (i, j) is base level.
inline bool is_base_level(int i, int j, int nx, int ny, BaseLevel base) {
  return i == 0 || i == nx - 1 || (base == BaseLevel::kAllEdges && (j == 0 || j == ny - 1));
}

// Priority-flood depression filling (Barnes et al. 2014) of `height` (nx × ny) in place: from the
// outlet vertices (`is_outlet(i, j)`) inwards, lowest first (a radix heap; equal heights last-in
// first-out); a vertex lower than the one that reached it is raised to that one's height plus
// `epsilon`, so every depression drains over its rim and flats drain towards their outlet. The one
// flood of the project: routing and the terrain metrics use it.
void priority_flood(std::vector<double>& height, int nx, int ny,
                    const std::function<bool(int, int)>& is_outlet, double epsilon);

// D8 routing of `height` (nx × ny, spacing `cell`) with the base-level edges fixed. Depressions
// are routed through, not into: receivers are the steepest descent on the surface filled by
// priority-flood (Barnes et al. 2014) with a tiny gradient across flats (ε = 1e-9 m per cell, kept
// out of the heights themselves), so every node drains to the edge and none to a pit.
FlowRouting route_d8(const std::vector<double>& height, int nx, int ny, double cell,
                     BaseLevel base = BaseLevel::kAllEdges);

// The stack and the area of given receivers (1-D profiles, tests): `cell_area` per node.
void build_stack(FlowRouting& routing, const std::vector<double>& cell_area);

}  // namespace runnel
