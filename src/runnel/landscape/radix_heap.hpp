// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

namespace runnel {

// A monotone priority queue of (double key, int32 value) pairs, smallest key first: a radix heap
// (Ahuja, Mehlhorn, Orlin & Tarjan 1990). Every pushed key must be at least the last popped one, as
// in a priority-flood, which pops in non-decreasing order. Push is O(1), pop amortised O(log of
// the key range), against O(log n) for each with a binary heap: on the flood of a 1024² grid the
// heap was most of the routing's time. Equal keys come out last-in first-out (deterministic).
class RadixHeap {
 public:
  void push(double key, std::int32_t value) {
    const std::uint64_t k = order(key);
    buckets_[bucket(k)].push_back({k, value});
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  // The smallest key's entry (removed), as (key, value).
  std::pair<double, std::int32_t> pop() {
    if (buckets_[0].empty()) refill();
    const auto [k, value] = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return {key_of(k), value};
  }

 private:
  // Doubles as unsigned integers in the same order (negatives included; no NaN).
  static std::uint64_t order(double key) {
    const auto bits = std::bit_cast<std::uint64_t>(key);
    return (bits >> 63) ? ~bits : bits | (std::uint64_t{1} << 63);
  }
  static double key_of(std::uint64_t k) {
    return std::bit_cast<double>((k >> 63) ? k & ~(std::uint64_t{1} << 63) : ~k);
  }
  // Bucket b > 0 holds keys whose highest bit differing from the last popped key is bit b − 1.
  int bucket(std::uint64_t k) const { return k == last_ ? 0 : 64 - std::countl_zero(k ^ last_); }
  // The first non-empty bucket's smallest key becomes the last; its entries spread into lower
  // buckets (at least one into bucket 0).
  void refill() {
    int b = 1;
    while (buckets_[b].empty()) ++b;
    std::uint64_t smallest = buckets_[b].front().first;
    for (const auto& e : buckets_[b]) smallest = std::min(smallest, e.first);
    last_ = smallest;
    for (const auto& e : buckets_[b]) buckets_[bucket(e.first)].push_back(e);
    buckets_[b].clear();
  }
  std::array<std::vector<std::pair<std::uint64_t, std::int32_t>>, 65> buckets_;
  std::uint64_t last_ = 0;
  std::size_t size_ = 0;
};

}  // namespace runnel
