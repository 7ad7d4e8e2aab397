// SPDX-License-Identifier: MIT
// Hydrostatic tank (Adami, Hu & Adams 2012): a water column of height H in a closed box whose floor
// is a flat terrain heightmap (the same boundary rain meets) and whose sides are the tank walls.
// The column starts at rest with uniform density ρ0 (not from the answer), with the run's own
// parameters, settles for `settle` seconds, and the pressure is averaged over the last quarter.
// Every particle is measured, the wall neighbourhoods and the free surface included. The free
// surface is where the fluid's volume Σ m/ρ puts it: floor + Σ(m/ρ)/A. Per layer of particles
// (bands dx thick above the floor): mean pressure p̄ against ρ0 g d̄, d̄ the layer's mean depth.
// relative_error is the worst layer's |p̄ − ρ0 g d̄| / (ρ0 g d̄); the mean over all particles,
// Σ|p̄_i − ρ0 g d̄_i| / Σ ρ0 g d̄_i, is reported beside it.
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

namespace {

// Per layer of the tank (by height above the floor): Σ depth, Σ pressure, Σ expected, count.
using LayerProfile = std::map<int, std::array<double, 4>>;

// pressure.csv: each layer's mean pressure against its depth, beside ρ0 g d (runnel.plot draws it).
void write_pressure_profile(const std::string& out_dir, const LayerProfile& profile) {
  const std::filesystem::path out(out_dir);
  write_file_atomically((out / "pressure.csv").string(), [&](std::FILE* f) {
    std::fprintf(f, "depth,pressure,expected,particles\n");
    for (auto& [layer, row] : profile) {
      std::fprintf(f, "%.6g,%.6g,%.6g,%.0f\n", row[0] / row[3], row[1] / row[3], row[2] / row[3],
                   row[3]);
    }
  });
}

// What the settling tank's final quarter gave, per particle and as a whole.
struct TankSamples {
  // Per particle (by its stable id): Σ depth, Σ pressure, Σ height above the floor.
  std::map<std::uint32_t, std::array<double, 3>> sums;
  int samples = 0;
  // Σ max(ρ/ρ0 − 1, 0) over the samples of every particle: the compression (a summation density
  // is below ρ0 at the free surface by construction, which is no error).
  double compression = 0;
  long long density_samples = 0;
};

// Steps the tank until `settle` and samples every tenth step of the final quarter.
TankSamples sample_settling_tank(SphSolver& solver, const SphSettings& s, double settle,
                                 double floor_height, double width, bool progress) {
  TankSamples t;
  const double average_from = 0.75 * settle;
  while (solver.time() < settle) {
    solver.step();
    if (solver.time() < average_from || solver.steps() % 10 != 0) continue;
    const HostParticles p = solver.particles().download();
    const std::vector<float> pressure = solver.pressure();
    double volume = 0;
    for (float rho : p.f[kRho]) volume += s.mass() / rho;
    const double surface = floor_height + volume / (width * width);
    for (std::size_t i = 0; i < p.size(); ++i) {
      auto& sum = t.sums[p.id[i]];
      sum[0] += surface - p.f[kY][i];
      sum[1] += pressure[i];
      sum[2] += p.f[kY][i] - floor_height;
      t.compression += std::max(p.f[kRho][i] / s.rho0 - 1.0, 0.0);
      ++t.density_samples;
    }
    ++t.samples;
    if (progress) std::fprintf(stderr, "hydrostatic: t = %.3f / %.3f s\r", solver.time(), settle);
  }
  if (progress) std::fprintf(stderr, "\n");
  return t;
}

}  // namespace

ValidationResult validate_hydrostatic(ComputeContext& compute, const ValidationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int layers = options.resolution > 0 ? options.resolution : 16;
  const double height = 0.4;  // m, in a box 0.25 m wide whatever the resolution
  const int width_cells = std::max(4, static_cast<int>(std::lround(0.625 * layers)));
  const double floor_height = 1.0;  // m: the terrain floor is not at zero
  const double dx = height / layers;
  Parameters params = options.params;
  params.set("sph.walls", true, "validate");
  SphSettings s = SphSettings::from(params, dx, std::sqrt(params.real("sph.gravity") * height));
  const double width = width_cells * dx;

  Heightmap floor = flat_floor(2 * width_cells, 2 * width_cells, 0.5 * dx);
  for (float& h : floor.h) h = static_cast<float>(floor_height);
  SphSolver solver(compute, s, floor, floor_height + 1.5 * height);
  HostParticles block = uniform_block(s, width, height, width);
  for (float& y : block.f[kY]) y += static_cast<float>(floor_height);
  solver.add(block);
  const long long particles = static_cast<long long>(solver.particles().size());
  // Long enough for the acoustic ringing of the uniform start to die down under the run's own
  // viscosity (about 100 crossings of the column by sound).
  const double settle =
      options.settle_time > 0 ? options.settle_time : 50.0 * std::sqrt(height / s.gravity);

  const TankSamples t =
      sample_settling_tank(solver, s, settle, floor_height, width, options.progress);
  const auto& sums = t.sums;
  const int samples = t.samples;
  double abs_error = 0, expected_sum = 0;
  LayerProfile profile;
  for (auto& [id, sum] : sums) {
    const double depth = sum[0] / samples, pressure = sum[1] / samples;
    const double expected = s.rho0 * s.gravity * depth;
    abs_error += std::fabs(pressure - expected);
    expected_sum += expected;
    auto& row = profile[static_cast<int>(std::floor(sum[2] / samples / dx))];
    row[0] += depth;
    row[1] += pressure;
    row[2] += expected;
    row[3] += 1;
  }
  double worst_layer = 0, worst_depth = 0, worst_below_surface = 0;
  const int top_layer = profile.empty() ? 0 : profile.rbegin()->first;
  for (auto& [layer, row] : profile) {
    const double e = std::fabs(row[1] - row[2]) / row[2];
    if (e > worst_layer) worst_layer = e, worst_depth = row[0] / row[3];
    if (layer != top_layer) worst_below_surface = std::max(worst_below_surface, e);
  }
  if (!options.out_dir.empty()) write_pressure_profile(options.out_dir, profile);
  ValidationResult r;
  r.name = "hydrostatic";
  r.particles = particles;
  r.steps = static_cast<long long>(solver.steps());
  r.relative_error = worst_layer;
  r.target = 0.03;
  // Water at rest is incompressible: the mean of max(ρ/ρ0 − 1, 0) at most 0.1 %.
  const double mean_compression = t.density_samples > 0 ? t.compression / t.density_samples : 0.0;
  const double compression_target = 0.001;
  r.other_targets_met = mean_compression <= compression_target;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.details.add("layers", layers)
      .add("dx", dx)
      .add("height", height)
      .add("c0", s.c0)
      .add("alpha_visc", s.alpha_visc)
      .add("sim_time", solver.time())
      .add("samples", samples)
      .add("worst_layer_relative_error", worst_layer)
      .add("worst_layer_depth", worst_depth)
      .add("worst_layer_below_surface_relative_error", worst_below_surface)
      .add("mean_relative_error", expected_sum > 0 ? abs_error / expected_sum : 1.0)
      .add("mean_compression", mean_compression)
      .add("mean_compression_target", compression_target)
      .add("solver", solver.solver_json())
      .add("start", "uniform density rho0, at rest")
      .add("floor", "flat terrain heightmap");
  return r;
}

JsonObject ValidationResult::summary() const {
  JsonObject o;
  o.add("case", name)
      .add("particles", particles)
      .add("steps", steps)
      .add("wall_seconds", wall_seconds)
      .add("relative_error", relative_error)
      .add("target", target)
      .add("passed", relative_error <= target && other_targets_met)
      .add("details", details);
  return o;
}

}  // namespace runnel
