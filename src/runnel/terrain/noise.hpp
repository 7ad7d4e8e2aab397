// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace runnel {

// 2-D gradient (Perlin-style) noise with hashed lattice gradients: deterministic per (seed,
// octave). Returns values in about [-0.7, 0.7], zero at lattice points.
double gradient_noise(double x, double y, std::uint64_t seed, std::uint64_t octave);

}  // namespace runnel
