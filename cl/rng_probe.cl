// SPDX-License-Identifier: MIT
// Exposes common.cl's counter-based generator, so a test can check the device draws the same bits
// as the host's rng.hpp.

__kernel void rng_probe(__global ulong* bits, __global float* uniform, __global float* keyed, const ulong seed,
                        const ulong stream, const ulong key) {
  const int k = get_global_id(0);
  bits[k] = rng_bits(seed, stream, (ulong)k);
  uniform[k] = rng_uniform(seed, stream, (ulong)k);
  keyed[k] = keyed_uniform(key, (uint)k);
}
