// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// One tunable of a generator, set with `--set key=value`.
struct GeneratorParam {
  std::string key;
  double default_value;
  std::string unit;
  std::string help;
  double min_value;
  double max_value;
  bool whole = false;  // a count: a fractional value is refused, not truncated
};

class ComputeContext;

struct GeneratorRequest {
  int nx = 257;
  int ny = 257;
  double cell = 1.0;  // m
  std::uint64_t seed = 1;
  std::map<std::string, double> values;  // every parameter of the generator, defaults filled in
  // The device for the noise families (null: the host, which gives the same bytes).
  ComputeContext* compute = nullptr;
};

struct GeneratorSpec {
  std::string name;
  std::string description;
  std::vector<GeneratorParam> params;
  std::function<Heightmap(const GeneratorRequest&)> make;
  bool on_device = false;  // runs on the request's OpenCL device when it has one
};

// Every terrain generator, in the order `runnel generate --help` lists them.
const std::vector<GeneratorSpec>& generators();
const GeneratorSpec& find_generator(
    const std::string& name);  // throws an input error naming the choices

// Generates a terrain: checks the size, fills defaults, and rejects unknown or out-of-range
// parameters with an input error that names the key. Deterministic for a given seed.
Heightmap generate_terrain(const std::string& name, int nx, int ny, double cell, std::uint64_t seed,
                           const std::map<std::string, double>& overrides = {},
                           ComputeContext* compute = nullptr);

}  // namespace runnel
