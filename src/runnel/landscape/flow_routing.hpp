// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "runnel/landscape/basin_graph.hpp"
#include "runnel/landscape/grid_neighbours.hpp"

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
// `epsilon`, so every depression drains over its rim and flats drain towards their outlet. Vertices
// above the flood keep their height and are traced uphill without the queue (Zhou, Sun & Fu 2016),
// so the queue holds only the depressions' vertices and the rims around them. With epsilon = 0 the
// result is the exact filled surface. The terrain metrics fill with it (an ε relative to the
// relief); routing fills through the basin graph instead (D8Router), which is faster on the large
// grids of long runs and equal to this with epsilon = 0 (tested).
void priority_flood(std::vector<double>& height, int nx, int ny,
                    const std::function<bool(int, int)>& is_outlet, double epsilon);

// D8 routing on one grid (spacing `cell`, the base-level edges fixed), its working memory kept
// from call to call: fresh pages for the ~60 MB a 1024² grid needs were a fifth of a step.
// Depressions are routed through, not into: the receivers are the steepest descent on the surface
// filled exactly by the basin graph (Cordonnier et al. 2019; basin_graph.hpp), and the vertices of
// a lake or flat drain breadth first to its outlet, as the ε gradient of priority-flood+ε (Barnes
// et al. 2014) would send them, without changing any height. Every node drains to base level.
class D8Router {
 public:
  D8Router(int nx, int ny, double cell, BaseLevel base = BaseLevel::kAllEdges);
  // Valid until the next call.
  const FlowRouting& route(const std::vector<double>& height);

 private:
  void steepest_descent(const std::vector<double>& surface, std::int32_t k);
  void drain_flats();

  int nx_, ny_;
  double cell_;
  GridNeighbours around_;
  std::vector<std::uint8_t> outlet_, pending_, waiting_;
  BasinGraph basins_;
  FlowRouting routing_;
  std::vector<double> filled_;
  std::vector<std::int32_t> flat_, reached_;
};

// One routing of `height` (nx × ny) with a router of its own.
FlowRouting route_d8(const std::vector<double>& height, int nx, int ny, double cell,
                     BaseLevel base = BaseLevel::kAllEdges);

// The stack and the area of given receivers (1-D profiles, tests): `cell_area` per node. Throws
// std::logic_error when the receivers hold a cycle or a node has more than 254 donors (a grid's
// nodes have at most 8).
void build_stack(FlowRouting& routing, const std::vector<double>& cell_area);

}  // namespace runnel
