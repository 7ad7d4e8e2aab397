// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/compute/context.hpp"

namespace runnel {

// A noise-family terrain (cl/terrain_noise_core.cl): the families, their parameters, and the grid.
struct NoiseFamily {
  enum Kind {
    kValue = 0,
    kTurbulence = 1,
    kMultifractal = 2,
    kHybrid = 3,
    kHetero = 4,
    kVaryingHurst = 5
  };
  Kind kind = kValue;
  int octaves = 8;
  bool cosine = true;       // value noise: cosine interpolation, else linear
  bool by_height = false;   // varying Hurst: with the first octaves' height, else with x
  double frequency = 0.01;  // cycles per metre of the first octave
  double lacunarity = 2.0;
  double hurst = 0.8;       // H (H1 for the varying family)
  double hurst_end = 0.3;   // H2 of the varying family
  double persistence = -1;  // value noise: amplitude ratio; < 0: lacunarity^−H
  double offset = 0.8;
  std::uint64_t seed = 1;
};

// Heights (unnormalised, metres of the noise's own scale) of every vertex of an nx × ny grid of
// spacing `cell`: on the device when `compute` is given, else on the host. The two agree bit for
// bit (the host is the device's oracle), and so do any two devices.
std::vector<float> noise_family_heights(const NoiseFamily& family, int nx, int ny, double cell,
                                        ComputeContext* compute);

}  // namespace runnel
