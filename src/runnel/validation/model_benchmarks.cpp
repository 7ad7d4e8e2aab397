// SPDX-License-Identifier: MIT
// `runnel bench droplet|olsen|thermal|pipe`: a model on an fBm terrain, timed after a warm-up step,
// with per-kernel times from OpenCL profiling events.
#include <chrono>
#include <functional>

#include "runnel/models/droplet_model.hpp"
#include "runnel/models/olsen_model.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/thermal.hpp"
#include "runnel/validation/sph_benchmark.hpp"

namespace runnel {
namespace {

struct Timing {
  double seconds = 0;
  JsonObject kernels;
};

// One warm-up call (kernel builds), then `steps` timed calls of `advance`.
Timing time_steps(ComputeContext& compute, int steps, const std::function<void()>& advance) {
  advance();
  compute.queue().finish();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) advance();
  compute.queue().finish();
  Timing t;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& [name, v] : profiler.collect()) t.kernels.add(name, v);
  profiler.enable(false);
  return t;
}

// The JSON of a grid model's benchmark: cell-steps per second.
JsonObject grid_result(ComputeContext& compute, const char* model, int size, int steps,
                       const Timing& t) {
  return JsonObject()
      .add("benchmark", model)
      .add("device", compute.info().name)
      .add("size", size)
      .add("steps", steps)
      .add("seconds", t.seconds)
      .add("cell_steps_per_second", static_cast<double>(size) * size * steps / t.seconds)
      .add("kernel_seconds", t.kernels);
}

Heightmap bench_terrain(int size, double relief) {
  return generate_terrain("fbm", size, size, 1.0, 1, {{"relief", relief}});
}

}  // namespace

JsonObject benchmark_droplet(ComputeContext& compute, int size, int batches,
                             const Parameters& params) {
  DeviceTerrain terrain(compute, bench_terrain(size, 0.25));
  const DropletSettings s = DropletSettings::from(params);
  DropletModel model(compute, terrain, s, 1);
  std::uint64_t first = 0;
  bool warm = false;
  const Timing t = time_steps(compute, batches, [&] {
    model.advance();
    if (!warm) {  // the warm-up batch is not counted
      first = model.droplets();
      warm = true;
    }
  });
  const double droplets = static_cast<double>(model.droplets() - first);
  return JsonObject()
      .add("benchmark", "droplet")
      .add("device", compute.info().name)
      .add("size", size)
      .add("batches", batches)
      .add("droplets", droplets)
      .add("lifetime", s.lifetime)
      .add("seconds", t.seconds)
      // Every droplet is counted for its whole lifetime; those that leave the map early did less
      // work.
      .add("droplet_steps_per_second", droplets * s.lifetime / t.seconds)
      .add("kernel_seconds", t.kernels);
}

JsonObject benchmark_olsen(ComputeContext& compute, int size, int iterations,
                           const Parameters& params) {
  DeviceTerrain terrain(compute, bench_terrain(size, 0.1));
  OlsenModel model(compute, terrain, OlsenSettings::from(params));
  return grid_result(compute, "olsen", size, iterations,
                     time_steps(compute, iterations, [&] { model.advance(); }));
}

JsonObject benchmark_thermal(ComputeContext& compute, int size, int iterations,
                             const Parameters& params) {
  DeviceTerrain terrain(compute, bench_terrain(size, 0.5));
  ThermalSettings s;
  s.talus_angle_deg = params.real("thermal.talus_angle");
  s.rate = params.real("thermal.rate");
  s.height_aware = params.boolean("thermal.height_aware");
  s.hardness = params.real("thermal.hardness");
  ThermalRelaxation thermal(compute, terrain, s);
  return grid_result(compute, "thermal", size, iterations,
                     time_steps(compute, iterations, [&] { thermal.relax(); }));
}

JsonObject benchmark_pipe(ComputeContext& compute, int size, int steps, const Parameters& params) {
  DeviceTerrain terrain(compute, bench_terrain(size, 0.1));
  PipeModel model(compute, terrain, PipeSettings::from(params));
  return grid_result(compute, "pipe", size, steps,
                     time_steps(compute, steps, [&] { model.advance(); }));
}

}  // namespace runnel
