// SPDX-License-Identifier: MIT
#pragma once
#include <map>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/terrain/generators.hpp"

namespace runnel {

// One parameter of a terrain filter, as a graph node sets it (docs/generators.md): described as a
// generator's parameter is.
using FilterParam = GeneratorParam;

// A filter of the terrain graph: a function of its inputs (all on one grid) and its parameters.
struct FilterSpec {
  std::string name;
  std::string description;
  int min_inputs, max_inputs;  // how many inputs it takes
  std::vector<FilterParam> params;
  Heightmap (*apply)(const std::vector<const Heightmap*>& inputs,
                     const std::map<std::string, double>& values);
};

// Every filter: scale, normalise, power, smoothstep, abs, smooth, terrace, blend, max, min, median,
// add. Those that reshape heights (power, smoothstep, abs, terrace) work on the input's heights
// mapped to [0, 1] by its own range and map back to that range.
const std::vector<FilterSpec>& filters();
const FilterSpec* find_filter(const std::string& name);

}  // namespace runnel
