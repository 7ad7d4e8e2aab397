// SPDX-License-Identifier: MIT
// Erosion convergence: the same rain on the same terrain, computed again with half the time step,
// with particles of half the size (the same rain volume: eight times as many), with drops spawned
// at 0.5 and 2 spacings instead of 1, and with twice the speed of sound (a stiffer, less
// compressible fluid: weakly compressible SPH approximates water only while c0 does not matter).
// A result that moves with a numerical knob is an artefact, so each variant is compared with the
// base run: its eroded volume (cell²·Σ max(0, h0 − h)), and for the finer particles the
// correlation of the Δh maps smoothed over 4 cells (reported for every variant, asserted for the
// finer particles). A run with another seed shows how far runs differ by chance alone (reported,
// no target).
// The terrain: fBm hills like the default scenario's, `resolution` vertices per side (default 65,
// 2 m cells), or the user's; rain at a constant intensity (60,000 mm/h on 2 m cells: the water is
// resolved, several particles on a footprint; in proportion to the cell on other terrains, so that
// the depth it lays down keeps its ratio to the particle spacing, half a cell) over the whole
// terrain for `sim_time` seconds; drops live until they leave the map, so the rain volume is the
// only water.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "runnel/core/text.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/sph/sph_settings.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel {
namespace {

struct ErosionRun {
  double eroded = 0;       // m³
  double sound_speed = 0;  // m/s, the c0 the run used
  // The weakly compressible fluid's own check, over every step: the largest |v|/c0 and ρ/ρ0 − 1.
  double peak_mach = 0, peak_compression = 0;
  Heightmap before, after;
  long long spawned = 0, steps = 0;
  double wall_seconds = 0;
  WaterResolution water;  // at the end: how many of the particles on the bed are films
};

ErosionRun run_rain(ComputeContext& compute, const Parameters& params, const Heightmap& terrain,
                    double sim_time) {
  const auto start = std::chrono::steady_clock::now();
  SphModel model(compute, params, terrain);
  ErosionRun r;
  const SphSolver& solver = model.simulation().solver();
  model.advance(sim_time, [&] {
    const SphHealth& h = solver.health();
    r.peak_mach = std::max(r.peak_mach, h.v_max / solver.settings().c0);
    r.peak_compression = std::max(r.peak_compression, h.rho_max / solver.settings().rho0 - 1.0);
  });
  r.before = model.initial_terrain();
  r.after = model.terrain();
  r.eroded = model.mass_balance().eroded;
  r.sound_speed = model.sound_speed();
  r.spawned = static_cast<long long>(model.drops_spawned());
  r.steps = static_cast<long long>(model.steps());
  r.water = model.water_resolution();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// Δh = after − before, averaged over a window of `width` cells (clamped at the edges).
std::vector<double> smoothed_change(const ErosionRun& r, int width) {
  const Heightmap& a = r.after;
  const int half = width / 2;
  std::vector<double> out(a.size());
  for (int j = 0; j < a.ny; ++j) {
    for (int i = 0; i < a.nx; ++i) {
      double sum = 0;
      int n = 0;
      for (int dj = -half; dj <= half; ++dj) {
        for (int di = -half; di <= half; ++di) {
          const int x = std::clamp(i + di, 0, a.nx - 1), z = std::clamp(j + dj, 0, a.ny - 1);
          sum += double(a.at(x, z)) - r.before.at(x, z);
          ++n;
        }
      }
      out[static_cast<std::size_t>(j) * a.nx + i] = sum / n;
    }
  }
  return out;
}

// The base run's parameters: the user's, with a storm heavy enough that the water on each footprint
// is several particles at the base resolution (docs/erosion.md: below that the films are not
// resolved, and drops of half the size claim more bed), and the spacing and spawn height fixed.
Parameters convergence_base(const Parameters& given, double cell) {
  Parameters base = given;
  auto set_default = [&](const char* key, auto value) {
    if (!base.was_set(key)) base.set(key, value, "validate");
  };
  set_default("rain.intensity", 60000.0 * cell / 2.0);  // mm/h
  set_default("rain.lifespan", 1e9);                    // water leaves only through the map's edges
  // Far above what 20 s of this rain can spawn (about 44,000 particles at half the spacing), so
  // it never binds, and within any device's memory.
  set_default("rain.max_particles", static_cast<std::int64_t>(2000000));
  set_default("erosion.morphological_factor", 100.0);
  const double spacing = particle_spacing(base, cell);
  base.set("sph.spacing", spacing, "validate");
  base.set("rain.spawn_height", spacing, "validate");
  return base;
}

struct Variant {
  const char* name;
  Parameters params = default_parameters();
};

// The base run and one run per knob: half the step, half the spacing, the spawn height halved
// and doubled.
std::vector<Variant> knob_variants(const Parameters& base, double spacing) {
  std::vector<Variant> variants = {{"base", base}};
  // Half the time step: wcsph's acoustic CFL factor; dfsph's flow CFL factor and its cap (the
  // default scenario's dfsph steps are mostly the cap's).
  Parameters half_cfl = base;
  if (base.text("sph.solver") == "dfsph") {
    half_cfl.set("sph.cfl_flow", 0.5 * base.real("sph.cfl_flow"), "validate");
    const double dt_max = SphSettings::from(base, spacing, 1.0).dt_max;  // 0 resolved
    half_cfl.set("sph.dt_max", 0.5 * dt_max, "validate");
  } else {
    half_cfl.set("sph.cfl", 0.5 * base.real("sph.cfl"), "validate");
  }
  variants.push_back({"half_cfl", half_cfl});
  Parameters half_spacing = base;
  half_spacing.set("sph.spacing", 0.5 * spacing, "validate");
  half_spacing.set("rain.spawn_height", 0.5 * spacing, "validate");
  variants.push_back({"half_spacing", half_spacing});
  for (double spawn : {0.5, 2.0}) {
    Parameters p = base;
    p.set("rain.spawn_height", spawn * spacing, "validate");
    variants.push_back({spawn < 1 ? "spawn_0.5dx" : "spawn_2dx", p});
  }

  return variants;
}

// metrics.json's table: every run's eroded volume, its change and Δh correlation with the base.
std::vector<JsonObject> runs_table(const std::vector<Variant>& variants,
                                   const std::vector<ErosionRun>& runs,
                                   const std::vector<double>& correlation_with_base) {
  const double eroded = runs[0].eroded;
  std::vector<JsonObject> table;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const double correlation = correlation_with_base[k];
    table.push_back(
        JsonObject()
            .add("variant", variants[k].name)
            .add("eroded_m3", runs[k].eroded)
            .add("relative_change", k == 0 ? 0.0 : std::fabs(runs[k].eroded - eroded) / eroded)
            .add("dh_correlation_with_base", correlation)
            .add("peak_mach", runs[k].peak_mach)
            .add("peak_compression", runs[k].peak_compression)
            .add("film_share", runs[k].water.film_share)
            .add("unresolved_share", runs[k].water.unresolved_share)
            .add("particles_spawned", runs[k].spawned)
            .add("steps", runs[k].steps)
            .add("wall_seconds", runs[k].wall_seconds));
  }
  return table;
}

// Runs every variant, then the two whose settings follow from the base run: twice the c0 it
// derived from the terrain, and another seed.
std::vector<ErosionRun> run_variants(ComputeContext& compute, std::vector<Variant>& variants,
                                     const Parameters& base, const Heightmap& terrain,
                                     double sim_time, bool progress) {
  std::vector<ErosionRun> runs;
  auto run_variant = [&](const Variant& v) {
    if (progress) std::fprintf(stderr, "erosion-convergence: %s\n", v.name);
    runs.push_back(run_rain(compute, v.params, terrain, sim_time));
  };
  for (const auto& v : variants) run_variant(v);
  // Twice the c0 the base run derived from the terrain (or was given). It also halves the time
  // step, which half_cfl shows alone.
  Parameters stiffer = base;
  stiffer.set("sph.c0", 2.0 * runs[0].sound_speed, "validate");
  variants.push_back({"double_c0", stiffer});
  run_variant(variants.back());
  // The same run with other random numbers (other drops, other roundings): how far two runs that
  // no knob separates differ, the floor under every other variant's change and correlation. Under
  // light rain few particles draw the Δh map, and its correlation with the base run's is no higher
  // than this one's.
  Parameters reseeded = base;
  reseeded.set("run.seed", base.integer("run.seed") + 1, "validate");
  variants.push_back({"reseeded", reseeded});
  run_variant(variants.back());

  return runs;
}

}  // namespace

ValidationResult validate_erosion_convergence(ComputeContext& compute,
                                              const ValidationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int size = options.resolution > 0 ? options.resolution : 65;
  const double sim_time = options.settle_time > 0 ? options.settle_time : 20.0;
  const bool own_terrain = options.terrain.size() > 0;
  const Heightmap terrain =
      own_terrain ? options.terrain
                  : generate_terrain("fbm", size, size, 2.0, 7,
                                     {{"relief", 0.12}, {"hurst", 1.0}, {"octaves", 6}});
  const double cell = terrain.cell;
  const Parameters base = convergence_base(options.params, cell);
  const double spacing = base.real("sph.spacing");
  std::vector<Variant> variants = knob_variants(base, spacing);  // run_variants adds two
  const std::vector<ErosionRun> runs =
      run_variants(compute, variants, base, terrain, sim_time, options.progress);
  const double eroded = runs[0].eroded;
  auto change = [&](std::size_t k) { return std::fabs(runs[k].eroded - eroded) / eroded; };
  // Each variant's Δh map against the base run's (the base against itself: 1).
  const std::vector<double> base_change = smoothed_change(runs[0], 4);
  std::vector<double> correlation_with_base(runs.size(), 1.0);
  for (std::size_t k = 1; k < runs.size(); ++k)
    correlation_with_base[k] =
        metrics::pearson_correlation(base_change, smoothed_change(runs[k], 4));
  const double correlation = correlation_with_base[2];
  const double spawn_change = std::max(change(3), change(4));
  const double c0_change = change(5);

  ValidationResult r;
  r.name = "erosion-convergence";
  for (const auto& run : runs) {
    r.particles += run.spawned;
    r.steps += run.steps;
  }
  // The worst of the five criteria, each as a fraction of its tolerance (≤ 1 passes).
  const double scores[5] = {change(1) / 0.10, change(2) / 0.25, (1.0 - correlation) / 0.3,
                            spawn_change / 0.20, c0_change / 0.10};
  r.relative_error = *std::max_element(scores, scores + 5);
  r.target = 1.0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<JsonObject> table = runs_table(variants, runs, correlation_with_base);
  r.details
      .add("terrain", (own_terrain ? options.terrain_name : std::string("fbm")) + " " +
                          std::to_string(terrain.nx) + "x" + std::to_string(terrain.ny) + ", " +
                          format_number(cell) + " m cells")
      .add("rain_intensity_mm_per_h", base.real("rain.intensity"))
      .add("sim_time", sim_time)
      .add("runs", table)
      .add("half_cfl_change", change(1))
      .add("half_cfl_target", 0.10)
      .add("half_spacing_change", change(2))
      .add("half_spacing_target", 0.25)
      .add("half_spacing_dh_correlation", correlation)
      .add("half_spacing_correlation_target", 0.7)
      .add("spawn_height_change", spawn_change)
      .add("spawn_height_target", 0.20)
      .add("base_c0_m_per_s", runs[0].sound_speed)
      .add("double_c0_change", c0_change)
      .add("double_c0_target", 0.10)
      .add("reseeded_change", change(6))
      .add("reseeded_dh_correlation", correlation_with_base[6])
      .add("base_peak_mach", runs[0].peak_mach)
      .add("base_peak_compression", runs[0].peak_compression)
      .add("double_c0_peak_mach", runs[5].peak_mach)
      .add("double_c0_peak_compression", runs[5].peak_compression)
      .add("score", "relative_error is the worst criterion as a fraction of its tolerance");
  return r;
}

}  // namespace runnel
