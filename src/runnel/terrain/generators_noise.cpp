// SPDX-License-Identifier: MIT
// The noise families (cl/terrain_noise_core.cl): on the request's device when it has one, else on
// the host, with the same bytes either way. docs/generators.md.
#include "runnel/terrain/generator_util.hpp"
#include "runnel/terrain/noise_family.hpp"

namespace runnel::generator_util {
namespace {

NoiseFamily family_of(const GeneratorRequest& r, NoiseFamily::Kind kind) {
  NoiseFamily f;
  f.kind = kind;
  const auto value = [&](const char* key, double fallback) {
    auto it = r.values.find(key);
    return it == r.values.end() ? fallback : it->second;
  };
  f.octaves = static_cast<int>(value("octaves", 8));
  f.lacunarity = value("lacunarity", 2.0);
  f.hurst = value("hurst", 0.8);
  f.hurst_end = value("hurst_end", 0.3);
  f.persistence = value("persistence", -1.0);
  f.offset = value("offset", 0.8);
  f.cosine = value("interpolation", 1) >= 1;
  f.by_height = value("by_height", 0) >= 1;
  f.frequency = value("frequency", 2.0) / extent(r);
  f.seed = r.seed;
  return f;
}

Heightmap noise_terrain(const GeneratorRequest& r, NoiseFamily::Kind kind) {
  Heightmap t(r.nx, r.ny, r.cell);
  t.h = noise_family_heights(family_of(r, kind), r.nx, r.ny, r.cell, r.compute);
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

}  // namespace

Heightmap value_noise_terrain(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kValue);
}
Heightmap turbulence(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kTurbulence);
}
Heightmap multifractal(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kMultifractal);
}
Heightmap hybrid_multifractal(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kHybrid);
}
Heightmap hetero_terrain(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kHetero);
}
Heightmap varying_hurst(const GeneratorRequest& r) {
  return noise_terrain(r, NoiseFamily::kVaryingHurst);
}

}  // namespace runnel::generator_util
