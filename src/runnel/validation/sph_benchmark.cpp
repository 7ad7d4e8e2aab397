// SPDX-License-Identifier: MIT
#include "runnel/validation/sph_benchmark.hpp"

#include <chrono>
#include <cmath>

#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"

namespace runnel {

JsonObject benchmark_sph(ComputeContext& compute, long long particles, int steps,
                         const Parameters& params_in, unsigned tile) {
  // A block twice as wide as it is high, filling the tank's floor: the water is 1 m deep.
  const int high = std::max(2, static_cast<int>(std::lround(std::cbrt(particles / 4.0))));
  const int wide =
      std::max(2, static_cast<int>(std::lround(std::sqrt(static_cast<double>(particles) / high))));
  const double depth = 1.0, dx = depth / high;
  Parameters params = params_in;
  params.set("sph.walls", true, "bench");
  const SphSettings s =
      SphSettings::from(params, dx, std::sqrt(params.real("sph.gravity") * depth));
  SphSolver solver(compute, s, flat_floor(1, 1, wide * dx), 1.5 * depth);
  if (tile > 0) solver.hash().set_tile(tile);
  solver.add(hydrostatic_block(s, wide * dx, depth, wide * dx));
  const long long n = static_cast<long long>(solver.particles().size());

  for (int k = 0; k < 3; ++k) solver.step();  // warm-up: kernel builds, first allocations
  compute.queue().finish();
  KernelProfiler& profiler = compute.profiler();
  profiler.reset();
  profiler.enable(true);
  const double sim_start = solver.time();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) solver.step();
  compute.queue().finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& kernel_seconds = profiler.collect();
  profiler.enable(false);

  JsonObject kernels;
  double kernel_total = 0;
  for (auto& [name, t] : kernel_seconds) {
    kernels.add(name, t);
    kernel_total += t;
  }
  JsonObject out;
  out.add("benchmark", "sph")
      .add("device", compute.info().name)
      .add("particles", n)
      .add("steps", steps)
      .add("seconds", seconds)
      .add("particle_steps_per_second", n * static_cast<double>(steps) / seconds)
      .add("solver", s.solver)
      // The figure of merit across solvers: their steps differ 15-fold in length.
      .add("simulated_seconds", solver.time() - sim_start)
      .add("simulated_seconds_per_wall_second", (solver.time() - sim_start) / seconds)
      .add("spacing", dx)
      .add("h_factor", s.h / s.spacing)
      .add("tile", static_cast<long long>(solver.hash().tile_size()))
      .add("bytes_per_particle", static_cast<long long>(ParticleStore::bytes_per_particle()))
      .add("kernel_seconds_total", kernel_total)
      .add("device_idle_seconds", profiler.idle_seconds())
      .add("kernel_seconds", kernels);
  if (solver.dfsph()) out.add("dfsph", solver.dfsph()->json());
  return out;
}

}  // namespace runnel
