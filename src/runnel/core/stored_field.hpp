// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace runnel {

// One vertex field as a checkpoint stores it under /fields (float32 or int64 values, ny × nx ×
// components, interleaved per vertex): a grid model's fields and the layer stack's.
struct StoredField {
  std::string name;
  int components = 1;
  std::vector<float> f32;
  std::vector<std::int64_t> i64;
};

}  // namespace runnel
