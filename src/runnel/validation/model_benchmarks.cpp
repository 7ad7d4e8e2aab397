// SPDX-License-Identifier: MIT
// `runnel bench droplet|olsen|thermal|pipe`: a model on an fBm terrain, timed after a warm-up step,
// with per-kernel times from OpenCL profiling events.
#include <chrono>
#include <functional>
#include <memory>
#include <vector>

#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/validation/sph_benchmark.hpp"

namespace runnel {
namespace {

struct Timing {
  double seconds = 0;
  double idle = 0;  // device idle between launches (KernelProfiler::waits)
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
  t.idle = profiler.idle_seconds();
  profiler.enable(false);
  return t;
}

// Relief of the benchmark terrain per model: droplets and water need slopes to run down, talus
// needs slopes steeper than its angle.
double bench_relief(const std::string& model) {
  if (model == "droplet") return 0.25;
  if (model == "thermal") return 0.5;
  return 0.1;
}

}  // namespace

JsonObject benchmark_model(ComputeContext& compute, const std::string& name, int size, int steps,
                           Parameters params) {
  params.set("run.model", name);
  const Heightmap terrain =
      generate_terrain("fbm", size, size, 1.0, 1, {{"relief", bench_relief(name)}});
  const std::unique_ptr<Model> model = make_model(compute, params, terrain);
  double work = 0;
  bool warm = false;
  const Timing t = time_steps(compute, steps, [&] {
    model->step();
    if (warm) work += model->step_work();  // the warm-up step is not counted
    warm = true;
  });
  JsonObject o;
  o.add("benchmark", name)
      .add("device", compute.info().name)
      .add("lanes", compute.lanes())
      .add("size", size)
      .add("steps", steps)
      .add("seconds", t.seconds)
      // Droplets are counted for their whole lifetime; those that leave the map early did less
      // work.
      .add(std::string(model->work_unit()) + "_per_second", work / t.seconds)
      .add("device_idle_seconds", t.idle)
      .add("kernel_seconds", t.kernels);
  return o;
}

JsonObject benchmark_generators(ComputeContext& compute, int size, int steps) {
  std::vector<JsonObject> results;
  for (const GeneratorSpec& g : generators()) {
    if (!g.on_device) continue;
    const Timing t = time_steps(
        compute, steps, [&] { generate_terrain(g.name, size, size, 1.0, 1, {}, &compute); });
    const double vertices = static_cast<double>(size) * size * steps;
    results.push_back(JsonObject()
                          .add("generator", g.name)
                          .add("seconds", t.seconds)
                          .add("vertices_per_second", vertices / t.seconds)
                          .add("device_idle_seconds", t.idle)
                          .add("kernel_seconds", t.kernels));
  }
  return JsonObject()
      .add("benchmark", "generate")
      .add("device", compute.info().name)
      .add("lanes", compute.lanes())
      .add("size", size)
      .add("steps", steps)
      .add("generators", results);
}

}  // namespace runnel
