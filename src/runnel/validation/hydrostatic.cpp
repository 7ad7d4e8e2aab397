// SPDX-License-Identifier: MIT
// Hydrostatic tank (Adami, Hu & Adams 2012): a water column of height H at rest in a closed box.
// After settling, the pressure at depth d must be ρ0·g·d. Only the core of the column is measured
// (particles farther than 2h from the side walls, whose mirror model carries part of the weight).
// The column starts with the hydrostatic density, runs for `settle` seconds, and the pressure is
// averaged over the last quarter. relative_error = Σ|p̄_i − ρ0 g d̄_i| / Σ ρ0 g d̄_i over the
// particles below the top three layers, p̄_i and d̄_i each particle's pressure and depth averaged
// over the last quarter (by particle id).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "runnel/io/atomic_file.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel {

ValidationResult validate_hydrostatic(ComputeContext& compute, const ValidationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int layers = options.resolution > 0 ? options.resolution : 16;
  const int width_cells = 10;  // particles across the box (each way)
  const double height = 0.4;   // m
  const double dx = height / layers;
  Parameters params = options.params;
  params.set("sph.walls", true, "validate");
  // A settling test: stronger artificial viscosity damps the acoustic waves of the start
  // (the reference state is at rest, so viscosity does not bias it).
  if (!params.was_set("sph.alpha_visc")) params.set("sph.alpha_visc", 0.1, "validate");
  SphSettings s = SphSettings::from(params, dx, std::sqrt(params.real("sph.gravity") * height));
  const double width = width_cells * dx;

  SphSolver solver(compute, s, flat_floor(1, 1, width), 1.5 * height);
  solver.add(hydrostatic_block(s, width, height, width));
  const long long particles = static_cast<long long>(solver.particles().size());
  const double settle = 8.0 * std::sqrt(height / s.gravity);  // about 40 acoustic crossings
  const double average_from = 0.75 * settle;

  // Per particle (by its stable id): Σ depth and Σ pressure over the samples of the final quarter.
  std::map<std::uint32_t, std::array<double, 2>> sums;
  int samples = 0;
  while (solver.time() < settle) {
    solver.step();
    if (solver.time() < average_from || solver.steps() % 10 != 0) continue;
    const HostParticles p = solver.particles().download();
    const std::size_t n = p.size();
    // Only the core of the column: particles whose kernel support does not reach a side wall.
    std::vector<std::size_t> core;
    for (std::size_t i = 0; i < n; ++i) {
      const double px = p.f[kX][i], pz = p.f[kZ][i];
      if (std::min({px, pz, width - px, width - pz}) >= 2.0 * s.h) core.push_back(i);
    }
    // The core's free surface: the mean height of its top layer plus half a spacing.
    std::vector<float> ys;
    for (std::size_t i : core) ys.push_back(p.f[kY][i]);
    std::sort(ys.begin(), ys.end());
    const std::size_t per_layer = ys.size() / layers;
    double top = 0;
    for (std::size_t k = ys.size() - per_layer; k < ys.size(); ++k) top += ys[k];
    const double surface = top / per_layer + 0.5 * dx;
    for (std::size_t i : core) {
      const double r = p.f[kRho][i] / s.rho0;
      auto& sum = sums[p.id[i]];
      sum[0] += surface - p.f[kY][i];
      sum[1] += s.tait_b() * (std::pow(r, 7.0) - 1.0);
    }
    ++samples;
    if (options.progress)
      std::fprintf(stderr, "hydrostatic: t = %.3f / %.3f s\r", solver.time(), settle);
  }
  if (options.progress) std::fprintf(stderr, "\n");

  // Per layer: Σ depth, Σ pressure, Σ expected, count.
  std::map<int, std::array<double, 4>> profile;
  double abs_error = 0, expected_sum = 0;
  for (auto& [id, sum] : sums) {
    const double depth = sum[0] / samples, pressure = sum[1] / samples;
    if (depth < 3.0 * dx) continue;  // the top three layers are excluded (kernel truncation)
    const double expected = s.rho0 * s.gravity * depth;
    abs_error += std::fabs(pressure - expected);
    expected_sum += expected;
    auto& row = profile[static_cast<int>(std::floor(depth / dx))];
    row[0] += depth;
    row[1] += pressure;
    row[2] += expected;
    row[3] += 1;
  }
  double worst_layer = 0;
  for (auto& [layer, row] : profile)
    worst_layer = std::max(worst_layer, std::fabs(row[1] - row[2]) / row[2]);
  if (!options.out_dir.empty()) {
    write_file_atomically(
        (std::filesystem::path(options.out_dir) / "pressure.csv").string(), [&](std::FILE* f) {
          std::fprintf(f, "depth,pressure,expected\n");
          for (auto& [layer, row] : profile) {
            std::fprintf(f, "%.6g,%.6g,%.6g\n", row[0] / row[3], row[1] / row[3], row[2] / row[3]);
          }
        });
  }
  ValidationResult r;
  r.name = "hydrostatic";
  r.particles = particles;
  r.steps = static_cast<long long>(solver.steps());
  r.relative_error = expected_sum > 0 ? abs_error / expected_sum : 1.0;
  r.target = 0.05;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.details.add("layers", layers)
      .add("dx", dx)
      .add("height", height)
      .add("c0", s.c0)
      .add("sim_time", solver.time())
      .add("samples", samples)
      .add("max_layer_relative_error", worst_layer);
  return r;
}

std::string ValidationResult::summary_json() const {
  JsonObject o;
  o.add("case", name)
      .add("particles", particles)
      .add("steps", steps)
      .add("wall_seconds", wall_seconds)
      .add("relative_error", relative_error)
      .add("target", target)
      .add("passed", relative_error <= target)
      .add("details", details);
  return o.str();
}

}  // namespace runnel
