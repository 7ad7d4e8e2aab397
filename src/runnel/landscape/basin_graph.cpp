// SPDX-License-Identifier: MIT
#include "runnel/landscape/basin_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace runnel {
namespace {

// A counting sort's bucket starts: first[b] .. first[b + 1] for the `count` of each of `buckets`.
template <class Count>
void bucket_starts(std::vector<std::int32_t>& first, std::int32_t buckets, Count&& count) {
  first.assign(static_cast<std::size_t>(buckets) + 1, 0);
  count([&](std::int32_t b) { ++first[b + 1]; });
  std::partial_sum(first.begin(), first.end(), first.begin());
}

std::int32_t root_of(std::vector<std::int32_t>& parent, std::int32_t b) {
  while (parent[b] != b) b = parent[b] = parent[parent[b]];  // path halving
  return b;
}

}  // namespace

void BasinGraph::fill(const std::vector<double>& h, const std::vector<std::int32_t>& receiver,
                      const std::vector<std::uint8_t>& outlet, int nx, int ny,
                      std::vector<double>& filled) {
  label_basins(receiver, outlet);
  find_links(h, nx, ny);
  spill_levels();
  filled.resize(h.size());
  for (std::size_t k = 0; k < h.size(); ++k) filled[k] = std::max(h[k], spill_[basin_[k]]);
}

// Which basin every vertex drains to: 0 for the sea (every outlet), 1, 2, … for the pits in the
// order they are met. Each receiver chain is walked once.
void BasinGraph::label_basins(const std::vector<std::int32_t>& receiver,
                              const std::vector<std::uint8_t>& outlet) {
  const std::size_t n = receiver.size();
  basin_.assign(n, -1);
  basins_ = 1;
  for (std::size_t start = 0; start < n; ++start) {
    std::int32_t k = static_cast<std::int32_t>(start);
    while (basin_[k] < 0) {
      if (receiver[k] == k) {
        basin_[k] = outlet[k] ? 0 : basins_++;
        break;
      }
      path_.push_back(k);
      k = receiver[k];
    }
    for (const std::int32_t p : path_) basin_[p] = basin_[k];
    path_.clear();
  }
}

void BasinGraph::find_links(const std::vector<double>& h, int nx, int ny) {
  // Every adjacent pair of vertices once (east, south-west, south, south-east of each), in raster
  // order; a pair across a border is a candidate pass, its level the higher vertex's height.
  crossings_.clear();
  auto cross = [&](std::int32_t a, std::int32_t b) {
    const std::int32_t p = basin_[a], q = basin_[b];
    if (p == q) return;
    crossings_.push_back({std::max(h[a], h[b]), std::max(p, q), std::min(p, q)});
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int32_t k = j * nx + i;
      if (i + 1 < nx) cross(k, k + 1);
      if (j + 1 == ny) continue;
      if (i > 0) cross(k, k + nx - 1);
      cross(k, k + nx);
      if (i + 1 < nx) cross(k, k + nx + 1);
    }
  // Grouped by their higher basin (a counting sort), each pair of basins keeps its lowest
  // crossing: one link, found without a hash map.
  bucket_starts(first_, basins_, [&](auto add) {
    for (const Link& c : crossings_) add(c.higher);
  });
  by_higher_.resize(crossings_.size());
  cursor_.assign(first_.begin(), first_.end() - 1);
  for (const Link& c : crossings_) by_higher_[cursor_[c.higher]++] = c;
  links_.clear();
  link_to_.assign(basins_, -1);
  seen_from_.assign(basins_, -1);
  for (const Link& c : by_higher_) {
    if (seen_from_[c.lower] != c.higher) {
      seen_from_[c.lower] = c.higher;
      link_to_[c.lower] = static_cast<std::int32_t>(links_.size());
      links_.push_back(c);
    } else if (c.level < links_[link_to_[c.lower]].level) {
      links_[link_to_[c.lower]].level = c.level;
    }
  }
}

void BasinGraph::spill_levels() {
  // Kruskal from the lowest link (ties in the order found): a link that joins two trees is a pass
  // some water spills over.
  order_.resize(links_.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](std::int32_t a, std::int32_t b) {
    return links_[a].level < links_[b].level;
  });
  tree_root_.resize(basins_);
  std::iota(tree_root_.begin(), tree_root_.end(), 0);
  tree_.clear();
  for (const std::int32_t l : order_) {
    const std::int32_t a = root_of(tree_root_, links_[l].higher);
    const std::int32_t b = root_of(tree_root_, links_[l].lower);
    if (a == b) continue;
    tree_root_[a] = b;
    tree_.push_back(l);
  }
  // The tree as adjacency lists (first_ and cursor_ reused), then from the sea outwards: a basin
  // fills to the higher of its own pass and the level of the basin it spills into.
  bucket_starts(first_, basins_, [&](auto add) {
    for (const std::int32_t l : tree_) add(links_[l].higher), add(links_[l].lower);
  });
  adjacency_.resize(first_.back());
  cursor_.assign(first_.begin(), first_.end() - 1);
  for (const std::int32_t l : tree_) {
    adjacency_[cursor_[links_[l].higher]++] = l;
    adjacency_[cursor_[links_[l].lower]++] = l;
  }
  spill_.assign(basins_, std::numeric_limits<double>::quiet_NaN());
  spill_[0] = -std::numeric_limits<double>::infinity();
  path_.assign(1, 0);  // the walk's queue
  for (std::size_t q = 0; q < path_.size(); ++q) {
    const std::int32_t b = path_[q];
    for (std::int32_t e = first_[b]; e < first_[b + 1]; ++e) {
      const Link& link = links_[adjacency_[e]];
      const std::int32_t next = link.higher == b ? link.lower : link.higher;
      if (!std::isnan(spill_[next])) continue;
      spill_[next] = std::max(link.level, spill_[b]);
      path_.push_back(next);
    }
  }
  path_.clear();
}

}  // namespace runnel
