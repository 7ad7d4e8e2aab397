// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace runnel {

// Counter-based random numbers: a value is a pure function of (seed, stream, counter), so results
// do not depend on thread count or call order. The same functions exist in cl/common.cl; a test
// checks that the host and the device produce the same bits.
inline std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

inline std::uint64_t rng_bits(std::uint64_t seed, std::uint64_t stream, std::uint64_t counter) {
  return splitmix64(seed ^ splitmix64(stream ^ splitmix64(counter)));
}

// Uniform in [0, 1) with 24 random bits, exactly representable as float.
inline float rng_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t counter) {
  return static_cast<float>(rng_bits(seed, stream, counter) >> 40) * (1.0f / 16777216.0f);
}

// Uniform in [0, 1) with 53 random bits, for host-side generators.
inline double rng_uniform_double(std::uint64_t seed, std::uint64_t stream, std::uint64_t counter) {
  return static_cast<double>(rng_bits(seed, stream, counter) >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace runnel
