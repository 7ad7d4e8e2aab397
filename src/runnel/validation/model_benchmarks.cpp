// SPDX-License-Identifier: MIT
#include <chrono>

#include "runnel/models/droplet_model.hpp"
#include "runnel/models/olsen_model.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/thermal.hpp"
#include "runnel/validation/sph_benchmark.hpp"

namespace runnel {

JsonObject benchmark_droplet(ComputeContext& compute, int size, int batches,
                             const Parameters& params) {
  const Heightmap t = generate_terrain("fbm", size, size, 1.0, 1, {{"relief", 0.25}});
  DeviceTerrain terrain(compute, t);
  const DropletSettings s = DropletSettings::from(params);
  DropletModel model(compute, terrain, s, 1);
  model.advance();  // warm-up: kernel build
  compute.queue().finish();
  const std::uint64_t first = model.droplets();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < batches; ++k) model.advance();
  compute.queue().finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  JsonObject kernels;
  for (auto& [name, v] : profiler.collect()) kernels.add(name, v);
  profiler.enable(false);
  const double droplets = static_cast<double>(model.droplets() - first);
  return JsonObject()
      .add("benchmark", "droplet")
      .add("device", compute.info().name)
      .add("size", size)
      .add("batches", batches)
      .add("droplets", droplets)
      .add("lifetime", s.lifetime)
      .add("seconds", seconds)
      // Every droplet is counted for its whole lifetime; those that leave the map early did less
      // work.
      .add("droplet_steps_per_second", droplets * s.lifetime / seconds)
      .add("kernel_seconds", kernels);
}

}  // namespace runnel

namespace runnel {

JsonObject benchmark_olsen(ComputeContext& compute, int size, int iterations,
                           const Parameters& params) {
  const Heightmap t = generate_terrain("fbm", size, size, 1.0, 1, {{"relief", 0.1}});
  DeviceTerrain terrain(compute, t);
  OlsenModel model(compute, terrain, OlsenSettings::from(params));
  model.advance();  // warm-up: kernel builds
  compute.queue().finish();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < iterations; ++k) model.advance();
  compute.queue().finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  JsonObject kernels;
  for (auto& [name, v] : profiler.collect()) kernels.add(name, v);
  profiler.enable(false);
  const double cells = static_cast<double>(size) * size;
  return JsonObject()
      .add("benchmark", "olsen")
      .add("device", compute.info().name)
      .add("size", size)
      .add("steps", iterations)
      .add("seconds", seconds)
      .add("cell_steps_per_second", cells * iterations / seconds)
      .add("kernel_seconds", kernels);
}

}  // namespace runnel

namespace runnel {

JsonObject benchmark_thermal(ComputeContext& compute, int size, int iterations,
                             const Parameters& params) {
  const Heightmap t = generate_terrain("fbm", size, size, 1.0, 1, {{"relief", 0.5}});
  DeviceTerrain terrain(compute, t);
  ThermalSettings s;
  s.talus_angle_deg = params.real("thermal.talus_angle");
  s.rate = params.real("thermal.rate");
  s.height_aware = params.boolean("thermal.height_aware");
  s.hardness = params.real("thermal.hardness");
  ThermalRelaxation thermal(compute, terrain, s);
  thermal.relax();  // warm-up: kernel builds
  compute.queue().finish();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < iterations; ++k) thermal.relax();
  compute.queue().finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  JsonObject kernels;
  for (auto& [name, v] : profiler.collect()) kernels.add(name, v);
  profiler.enable(false);
  return JsonObject()
      .add("benchmark", "thermal")
      .add("device", compute.info().name)
      .add("size", size)
      .add("steps", iterations)
      .add("seconds", seconds)
      .add("cell_steps_per_second", static_cast<double>(size) * size * iterations / seconds)
      .add("kernel_seconds", kernels);
}

}  // namespace runnel

namespace runnel {

JsonObject benchmark_pipe(ComputeContext& compute, int size, int steps, const Parameters& params) {
  const Heightmap t = generate_terrain("fbm", size, size, 1.0, 1, {{"relief", 0.1}});
  DeviceTerrain terrain(compute, t);
  PipeModel model(compute, terrain, PipeSettings::from(params));
  model.advance();  // warm-up: kernel builds
  compute.queue().finish();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) model.advance();
  compute.queue().finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  JsonObject kernels;
  for (auto& [name, v] : profiler.collect()) kernels.add(name, v);
  profiler.enable(false);
  return JsonObject()
      .add("benchmark", "pipe")
      .add("device", compute.info().name)
      .add("size", size)
      .add("steps", steps)
      .add("seconds", seconds)
      .add("cell_steps_per_second", static_cast<double>(size) * size * steps / seconds)
      .add("kernel_seconds", kernels);
}

}  // namespace runnel
