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

// Numbers for every cell of a grid in one pass (the pipe model's stochastic rounding): the pass's
// (seed, stream, step) is mixed once on the host into a 64-bit key, and each cell's number is two
// rounds of a 32-bit bijective mix (Wellons' lowbias32) of its index under the key's halves. All
// 32-bit arithmetic, so a kernel over cells runs 8 or 16 wide where three 64-bit splitmix rounds a
// cell kept it 4 wide; distinct cells of one pass always get distinct bits.
inline std::uint64_t rng_key(std::uint64_t seed, std::uint64_t stream, std::uint64_t pass) {
  return rng_bits(seed, stream, pass);
}

inline std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  return x ^ (x >> 16);
}

// Uniform in [0, 1) with 24 random bits, exactly representable as float.
inline float keyed_uniform(std::uint64_t key, std::uint32_t counter) {
  const std::uint32_t bits = mix32(mix32(counter ^ static_cast<std::uint32_t>(key)) ^
                                   static_cast<std::uint32_t>(key >> 32));
  return static_cast<float>(bits >> 8) * (1.0f / 16777216.0f);
}

// Uniform in [0, 1) with 53 random bits, for host-side generators.
inline double rng_uniform_double(std::uint64_t seed, std::uint64_t stream, std::uint64_t counter) {
  return static_cast<double>(rng_bits(seed, stream, counter) >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace runnel
