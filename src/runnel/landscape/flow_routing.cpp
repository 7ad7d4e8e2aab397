// SPDX-License-Identifier: MIT
#include "runnel/landscape/flow_routing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "runnel/landscape/radix_heap.hpp"

namespace runnel {

namespace {

// The stack of r.receiver (donors first, as a topological order): from every source (a node no one
// drains to), in raster order, down its receivers for as long as the next one has all its donors
// in the order, adding r.area (each node's own on entry) on the way; then reversed. Walking down
// channels keeps the order, and so the erosion's pass over it, local in memory; no donor lists
// are needed. `waiting` is working memory.
void order_stack(FlowRouting& r, std::vector<std::uint8_t>& waiting) {
  const std::size_t n = r.receiver.size();
  constexpr std::uint8_t kInOrder = 0xff;
  waiting.assign(n, 0);  // donors not yet in the order: at most 8 on a grid (build_stack checks)
  for (std::size_t k = 0; k < n; ++k)
    if (r.receiver[k] != static_cast<std::int32_t>(k)) ++waiting[r.receiver[k]];
  r.stack.clear();
  r.stack.reserve(n);
  for (std::size_t source = 0; source < n; ++source) {
    if (waiting[source] != 0) continue;
    for (std::int32_t k = static_cast<std::int32_t>(source);;) {
      r.stack.push_back(k);
      waiting[k] = kInOrder;  // not a source when the raster scan reaches it
      const std::int32_t receiver = r.receiver[k];
      if (receiver == k) break;
      r.area[receiver] += r.area[k];
      if (--waiting[receiver] != 0) break;
      k = receiver;
    }
  }
  if (r.stack.size() != n)
    throw std::logic_error("flow routing: the receivers form a cycle, not a tree");
  std::reverse(r.stack.begin(), r.stack.end());
}

}  // namespace

void build_stack(FlowRouting& r, const std::vector<double>& cell_area) {
  // Any receivers, not a grid's: the byte that counts a node's donors must not wrap.
  std::vector<int> donors(r.receiver.size(), 0);
  for (std::size_t k = 0; k < r.receiver.size(); ++k)
    if (r.receiver[k] != static_cast<std::int32_t>(k) && ++donors[r.receiver[k]] > 254)
      throw std::logic_error("flow routing: a node with more than 254 donors");
  r.area = cell_area;
  std::vector<std::uint8_t> waiting;
  order_stack(r, waiting);
}

void priority_flood(std::vector<double>& filled, int nx, int ny,
                    const std::function<bool(int, int)>& is_outlet, double epsilon) {
  const std::size_t n = filled.size();
  const GridNeighbours around(nx, ny);
  std::vector<std::uint8_t> closed(n, 0);
  RadixHeap open;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (is_outlet(i, j)) {
        const std::int32_t k = j * nx + i;
        closed[k] = 1;
        open.push(filled[k], k);
      }
  // Zhou, Sun & Fu 2016's variant: a vertex above the flood level keeps its own height, and so does
  // every vertex uphill of it, so those are traced here without the queue (most of a landscape);
  // a traced vertex with a lower or equal neighbour still open goes into the queue at its height,
  // to flood that neighbour when its turn comes.
  std::vector<std::int32_t> uphill;
  auto trace_uphill = [&](std::int32_t start) {
    uphill.push_back(start);
    while (!uphill.empty()) {
      const std::int32_t t = uphill.back();
      uphill.pop_back();
      bool lower_open = false;
      around.visit(t, [&](std::int32_t m, int) {
        if (closed[m]) return;
        if (filled[m] > filled[t]) {
          closed[m] = 1;
          uphill.push_back(m);
        } else {
          lower_open = true;
        }
      });
      if (lower_open) open.push(filled[t], t);
    }
  };
  while (!open.empty()) {
    const auto popped = open.pop();  // not a structured binding: clang 14 cannot capture those
    const double level = popped.first;
    const std::int32_t k = popped.second;
    around.visit(k, [&](std::int32_t m, int) {
      if (closed[m]) return;
      closed[m] = 1;
      if (filled[m] > level) {
        trace_uphill(m);
      } else {  // in k's depression (or flat): raised just above k, so it drains towards k
        filled[m] = level + epsilon;
        open.push(filled[m], m);
      }
    });
  }
}

D8Router::D8Router(int nx, int ny, double cell, BaseLevel base)
    : nx_(nx),
      ny_(ny),
      cell_(cell),
      around_(nx, ny, cell),
      outlet_(static_cast<std::size_t>(nx) * ny, 0) {
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      outlet_[static_cast<std::size_t>(j) * nx + i] = is_base_level(i, j, nx, ny, base);
}

// k's steepest strictly downhill neighbour on `surface` as its receiver, or k itself when no
// neighbour is lower.
void D8Router::steepest_descent(const std::vector<double>& surface, std::int32_t k) {
  double steepest = 0;
  int towards = -1;
  around_.visit(k, [&](std::int32_t m, int d) {
    // Selects rather than a branch: which neighbour is steepest is a coin toss on rough ground.
    const double slope = (surface[k] - surface[m]) * around_.inverse_length(d);
    const bool steeper = slope > steepest;
    steepest = steeper ? slope : steepest;
    towards = steeper ? d : towards;
  });
  routing_.receiver[k] = towards < 0 ? k : around_.neighbour(k, towards);
  routing_.distance[k] = towards < 0 ? 0.0 : around_.length(towards);
}

const FlowRouting& D8Router::route(const std::vector<double>& height) {
  const std::size_t n = outlet_.size();
  FlowRouting& r = routing_;
  r.receiver.resize(n);
  r.distance.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (outlet_[k]) {
      r.receiver[k] = static_cast<std::int32_t>(k), r.distance[k] = 0;
      continue;
    }
    steepest_descent(height, static_cast<std::int32_t>(k));
  }
  // Where neither a vertex nor its receiver was raised, the steepest descent on the filled surface
  // is the one just found (filling only lessens the other slopes).
  basins_.fill(height, r.receiver, outlet_, nx_, ny_, filled_);
  flat_.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t rec = r.receiver[k];
    if (outlet_[k] || (rec != static_cast<std::int32_t>(k) && filled_[k] == height[k] &&
                       filled_[rec] == height[rec]))
      continue;
    steepest_descent(filled_, static_cast<std::int32_t>(k));
    if (r.receiver[k] == static_cast<std::int32_t>(k))
      flat_.push_back(static_cast<std::int32_t>(k));
  }
  drain_flats();
  r.area.assign(n, cell_ * cell_);
  order_stack(r, waiting_);
  return r;
}

// The vertices of lakes and flats (no lower neighbour on the filled surface) drain to a neighbour
// of their own level that is nearer, in steps, to one that drains: breadth first from those.
void D8Router::drain_flats() {
  FlowRouting& r = routing_;
  pending_.assign(filled_.size(), 0);
  for (const std::int32_t k : flat_) pending_[k] = 1;
  reached_.clear();
  for (const std::int32_t k : flat_) {
    around_.visit(k, [&](std::int32_t m, int d) {
      if (r.receiver[k] != k || pending_[m] || filled_[m] != filled_[k]) return;
      r.receiver[k] = m, r.distance[k] = around_.length(d);
    });
    if (r.receiver[k] != k) reached_.push_back(k);
  }
  for (const std::int32_t k : reached_) pending_[k] = 0;
  for (std::size_t q = 0; q < reached_.size(); ++q) {
    const std::int32_t k = reached_[q];
    around_.visit(k, [&](std::int32_t m, int d) {
      if (!pending_[m] || filled_[m] != filled_[k]) return;
      pending_[m] = 0;
      r.receiver[m] = k, r.distance[m] = around_.length(d);
      reached_.push_back(m);
    });
  }
  if (reached_.size() != flat_.size())
    throw std::logic_error("flow routing: a flat of the filled surface has no outlet");
}

FlowRouting route_d8(const std::vector<double>& height, int nx, int ny, double cell,
                     BaseLevel base) {
  D8Router router(nx, ny, cell, base);
  return router.route(height);
}

}  // namespace runnel
