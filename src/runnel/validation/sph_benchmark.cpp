// SPDX-License-Identifier: MIT
#include "runnel/validation/sph_benchmark.hpp"

#include <chrono>
#include <cmath>

#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"

namespace runnel {

namespace {

// A thin sheet two particles deep on a plane falling 10 % towards +x, in a closed tank: the shape
// of most of a storm's water (a film running downhill), where the pressure solves end at once.
constexpr double kSheetSlope = 0.1;
constexpr int kSheetLayers = 2;

Heightmap sloped_floor(int cells, double cell) {
  Heightmap floor = flat_floor(cells, cells, cell);
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      floor.at(i, j) = static_cast<float>(kSheetSlope * (cells - i) * cell);
  return floor;
}

HostParticles sheet_on_slope(const SphSettings& s, int side) {
  const double dx = s.spacing;
  HostParticles p;
  for (int k = 0; k < side; ++k)
    for (int layer = 0; layer < kSheetLayers; ++layer)
      for (int i = 0; i < side; ++i) {
        const double x = (i + 0.5) * dx;
        const double y = kSheetSlope * (side * dx - x) + (layer + 0.5) * dx;
        p.push(static_cast<float>(x), static_cast<float>(y), static_cast<float>((k + 0.5) * dx), 0,
               0, 0, static_cast<float>(s.rho0), 1e30f);
      }
  return p;
}

}  // namespace

JsonObject benchmark_sph(ComputeContext& compute, long long particles, int steps,
                         const Parameters& params_in, unsigned tile, const std::string& scene) {
  Parameters params = params_in;
  params.set("sph.walls", true, "bench");
  const bool sheet = scene == "sheet", fall = scene == "fall";
  // block: twice as wide as it is high, filling the tank's floor, the water 1 m deep.
  // fall: the same block at rest density, its bottom a quarter of its height above the floor of a
  //   tank twice as wide: it falls, lands (after 0.23 s) and spreads.
  // sheet: kSheetLayers particles of 5 cm deep on a square slope.
  const int high =
      sheet ? kSheetLayers : std::max(2, static_cast<int>(std::lround(std::cbrt(particles / 4.0))));
  const int wide =
      std::max(2, static_cast<int>(std::lround(std::sqrt(static_cast<double>(particles) / high))));
  const double dx = sheet ? 0.05 : 1.0 / high, depth = high * dx;
  const SphSettings s =
      SphSettings::from(params, dx,
                        std::sqrt(params.real("sph.gravity") * (sheet  ? 1.0
                                                                : fall ? 1.25 * depth
                                                                       : depth)));
  const double side = wide * dx, floor_side = fall ? 2 * side : side;
  SphSolver solver(compute, s, sheet ? sloped_floor(wide, dx) : flat_floor(1, 1, floor_side),
                   sheet  ? kSheetSlope * side + 1.0
                   : fall ? 2.0 * depth
                          : 1.5 * depth);
  if (tile > 0) solver.hash().set_tile(tile);
  if (fall) {
    HostParticles block = uniform_block(s, side, depth, side);
    for (float& x : block.f[kX]) x += static_cast<float>(side / 2);
    for (float& y : block.f[kY]) y += static_cast<float>(depth / 4);
    for (float& z : block.f[kZ]) z += static_cast<float>(side / 2);
    solver.add(std::move(block));
  } else {
    solver.add(sheet ? sheet_on_slope(s, wide) : hydrostatic_block(s, side, depth, side));
  }
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
      .add("scene", scene)
      .add("device", compute.info().name)
      .add("lanes", compute.lanes())
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
      .add("bytes_per_particle", static_cast<long long>(solver.bytes_per_particle()))
      .add("kernel_seconds_total", kernel_total)
      .add("device_idle_seconds", profiler.idle_seconds())
      .add("kernel_seconds", kernels);
  out.add("pressure_solver", solver.solver_json());
  return out;
}

}  // namespace runnel
