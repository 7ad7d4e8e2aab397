// SPDX-License-Identifier: MIT
// Host side of cl/terrain_noise.cl, and the host evaluation of the same arithmetic (compiled with
// -ffp-contract=off, CMakeLists.txt) that the device must match bit for bit.
#include "runnel/terrain/noise_family.hpp"

#include <cmath>

#include "runnel/compute/kernel.hpp"
#include "runnel/compute/launch.hpp"

namespace runnel {
namespace noise_core {
using uint = std::uint32_t;
#define RUNNEL_NOISE_HOST
#define NOISE_FLOOR std::floor
#define NOISE_FABS std::fabs
#define NOISE_GLOBAL
#include "../../../cl/terrain_noise_core.cl"
}  // namespace noise_core

namespace {

// Family 5's amplitude table: octave o at H = H1 + (H2 − H1)·s/16, lacunarity^(−H·o), in double
// and then rounded once, so the device only interpolates.
std::vector<float> amplitude_table(const NoiseFamily& f) {
  std::vector<float> table(NOISE_H_STEPS * static_cast<std::size_t>(f.octaves));
  for (int s = 0; s < NOISE_H_STEPS; ++s) {
    const double h = f.hurst + (f.hurst_end - f.hurst) * s / (NOISE_H_STEPS - 1);
    for (int o = 0; o < f.octaves; ++o)
      table[static_cast<std::size_t>(s) * f.octaves + o] =
          static_cast<float>(std::pow(f.lacunarity, -h * o));
  }
  return table;
}

noise_core::NoiseParams params_of(const NoiseFamily& f, int nx, double cell) {
  noise_core::NoiseParams p{};
  p.family = static_cast<int>(f.kind);
  p.octaves = f.octaves;
  p.cosine = f.cosine ? 1 : 0;
  p.by_height = f.by_height ? 1 : 0;
  p.frequency = static_cast<float>(f.frequency);
  p.lacunarity = static_cast<float>(f.lacunarity);
  p.gain =
      static_cast<float>(f.persistence >= 0 ? f.persistence : std::pow(f.lacunarity, -f.hurst));
  p.offset = static_cast<float>(f.offset);
  p.extent_x = static_cast<float>((nx - 1) * cell);
  p.seed_lo = static_cast<std::uint32_t>(f.seed);
  p.seed_hi = static_cast<std::uint32_t>(f.seed >> 32);
  return p;
}

}  // namespace

std::vector<float> noise_family_heights(const NoiseFamily& family, int nx, int ny, double cell,
                                        ComputeContext* compute) {
  const noise_core::NoiseParams p = params_of(family, nx, cell);
  const std::vector<float> amplitudes = amplitude_table(family);
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<float> h(n);
  const float c = static_cast<float>(cell);
  if (!compute) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        h[static_cast<std::size_t>(j) * nx + i] = noise_core::noise_family_height(
            &p, static_cast<float>(i) * c, static_cast<float>(j) * c, amplitudes.data());
    return h;
  }
  cl::Buffer out(compute->context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Buffer table(compute->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                   amplitudes.size() * sizeof(float), const_cast<float*>(amplitudes.data()));
  Kernel kernel(*compute, compute->program({"cl/terrain_noise_core.cl", "cl/terrain_noise.cl"}),
                "terrain_noise");
  kernel.set("height", out)
      .set("nx", nx)
      .set("ny", ny)
      .set("cell", c)
      .set("family", p.family)
      .set("octaves", p.octaves)
      .set("cosine", p.cosine)
      .set("by_height", p.by_height)
      .set("frequency", p.frequency)
      .set("lacunarity", p.lacunarity)
      .set("gain", p.gain)
      .set("offset", p.offset)
      .set("extent_x", p.extent_x)
      .set("seed_lo", static_cast<cl_uint>(p.seed_lo))
      .set("seed_hi", static_cast<cl_uint>(p.seed_hi))
      .set("amplitudes", table)
      .launch(round_up_work(n), "terrain.noise");
  compute->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * sizeof(float), h.data());
  return h;
}

}  // namespace runnel
