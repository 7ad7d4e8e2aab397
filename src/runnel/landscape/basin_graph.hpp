// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

namespace runnel {

// The exact depression-filled surface of an nx × ny grid, every vertex raised to the lowest level
// over which water from it can reach an outlet (no ε), from the graph of basins of Cordonnier, Bovy
// & Braun 2019: the vertices that `receiver` (steepest descent on `height`, a vertex its own
// receiver at an outlet or a pit) leads to the same pit form a basin, all outlets (`outlet[k]` ≠ 0)
// one sea; the lowest pass between every two adjacent basins is a link, the minimum spanning tree
// of the links (Kruskal) is the way each basin spills towards the sea, and a basin's vertices fill
// to the highest pass on that way. O(n) scans plus a sort of the links, against a priority queue
// over every vertex for a flood; the result equals priority_flood with epsilon = 0. The working
// memory is kept from call to call.
class BasinGraph {
 public:
  void fill(const std::vector<double>& height, const std::vector<std::int32_t>& receiver,
            const std::vector<std::uint8_t>& outlet, int nx, int ny, std::vector<double>& filled);

 private:
  // The lowest pass between two adjacent basins, `higher` > `lower` in number: the lowest of the
  // heights of the higher vertex of each adjacent pair across their border.
  struct Link {
    double level;
    std::int32_t higher, lower;
  };
  void label_basins(const std::vector<std::int32_t>& receiver,
                    const std::vector<std::uint8_t>& outlet);
  void find_links(const std::vector<double>& height, int nx, int ny);
  void spill_levels();

  std::int32_t basins_ = 0;
  std::vector<std::int32_t> basin_, path_, first_, cursor_, link_to_, seen_from_;
  std::vector<Link> crossings_, by_higher_, links_;
  std::vector<std::int32_t> order_, tree_root_, tree_, adjacency_;
  std::vector<double> spill_;
};

}  // namespace runnel
