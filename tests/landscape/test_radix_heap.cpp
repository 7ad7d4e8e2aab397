// SPDX-License-Identifier: MIT
// The priority-flood's queue against a sort: every key comes out in order, negative heights and
// ties included, while keys no smaller than the last popped one keep arriving.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "runnel/landscape/radix_heap.hpp"

namespace runnel {
namespace {

TEST(RadixHeap, PopsInTheOrderOfASortAsKeysKeepArriving) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> height(-50.0, 300.0), rise(0.0, 2.0);
  RadixHeap heap;
  std::vector<double> pushed, popped;
  for (int k = 0; k < 2000; ++k) {
    const double h = k % 10 == 0 ? 12.5 : height(rng);  // some ties
    heap.push(h, k);
    pushed.push_back(h);
  }
  double last = -1e300;
  while (!heap.empty()) {
    const auto [h, value] = heap.pop();
    ASSERT_GE(h, last);
    last = h;
    popped.push_back(h);
    if (popped.size() < 30000 && value % 3 == 0) {  // a flood's neighbours: never below the front
      const double next = h + rise(rng);
      heap.push(next, value + 1);
      pushed.push_back(next);
    }
  }
  std::sort(pushed.begin(), pushed.end());
  EXPECT_EQ(popped, pushed) << "every key out once, in order";
}

}  // namespace
}  // namespace runnel
