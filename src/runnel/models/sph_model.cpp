// SPDX-License-Identifier: MIT
#include "runnel/models/sph_model.hpp"

#include <algorithm>
#include <cstdio>

#include "runnel/core/rain_units.hpp"
#include "runnel/models/water_binning.hpp"
#include "runnel/sph/water_depth_reference.hpp"

namespace runnel {

const ModelInfo& SphModel::model_info() {
  static const ModelInfo info{
      "sph",
      "Erosion_Runnel",
      "runnel's SPH rain erosion (docs/sph.md, docs/erosion.md); weakly compressible SPH after "
      "Monaghan 1994 with delta-SPH (Antuono et al. 2010), erosion after Kristof et al. 2009",
      "sph",
      ModelClock::kSeconds,
      true,
      {{kTopographicElevation, FieldIntent::kInOut},
       {"particle__position", FieldIntent::kOut},
       {"particle__velocity", FieldIntent::kOut},
       {"particle__density", FieldIntent::kOut},
       {"particle__sediment", FieldIntent::kOut},
       {"particle__age", FieldIntent::kOut},
       {"particle__lifespan", FieldIntent::kOut},
       {"particle__contacts", FieldIntent::kOut},
       {"particle__id", FieldIntent::kOut}},
      {"film_share", "unresolved_share", "median_particles_per_footprint"},
      96};  // water_resolution.hpp
  return info;
}

SphModel::SphModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : SphModel(std::make_unique<Simulation>(compute, params, terrain)) {}

SphModel::SphModel(std::unique_ptr<Simulation> simulation)
    : sim_(std::move(simulation)), scenario_rain_(sim_->rain().settings()) {}

void SphModel::restore(const CheckpointData& data) {
  sim_->restore(data);
  resolution_.reset();
  if (scenario_rain_.region == RainSettings::Region::kMask) {  // a restored mask's rain
    scenario_rain_ = sim_->rain().masked_rain();
    apply_rain();
  }
  if (!painted_.empty() || !global_rain_) apply_rain();  // the front end's rain outlives a restore
}

bool SphModel::paint_rain_mask(const std::vector<int>& vertices, float value) {
  if (!sim_->paint_rain_mask(vertices, value)) return false;
  scenario_rain_ = sim_->rain().masked_rain();
  apply_rain();
  return true;
}

// A sink: the particles over it reach the end of their lifespan, so this step's evaporation
// removes them and leaves their load where they are, as it does for any drop at the end of its
// life (the mass balance books it the same way).
void SphModel::drain_sinks() {
  ParticleStore& store = sim_->solver().particles();
  if (store.size() == 0) return;
  const std::vector<float> x = store.read_field(kX), z = store.read_field(kZ),
                           age = store.read_field(kAge);
  std::vector<float> lifespan = store.read_field(kLifespan);
  bool drained = false;
  for (const RainDisc& d : painted_) {
    if (d.rate >= 0) continue;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double dx = x[i] - d.x, dz = z[i] - d.z;
      if (dx * dx + dz * dz <= d.radius * d.radius && lifespan[i] > age[i]) {
        lifespan[i] = age[i];
        drained = true;
      }
    }
  }
  if (drained) store.upload_field(kLifespan, lifespan);
}

void SphModel::set_painted_rain(const std::vector<RainDisc>& discs) {
  painted_ = discs;
  apply_rain();
}

bool SphModel::set_global_rain(bool on) {
  global_rain_ = on;
  apply_rain();
  return true;
}

void SphModel::apply_rain() {
  RainSettings rain = scenario_rain_;
  const auto raining = std::find_if(painted_.begin(), painted_.end(),
                                    [](const RainDisc& d) { return d.rate > 0; });  // not sinks
  if (raining != painted_.end()) {
    const RainDisc& d = *raining;
    rain.rain_on_disc(d.x, d.z, d.radius, rain_intensity(d.rate), particle_spacing());
  } else {
    rain.enabled = rain.enabled && global_rain_;
  }
  sim_->rain().settings() = rain;
}

WaterView SphModel::water_view() {
  const HostParticles p = particles();
  const Heightmap& t = sim_->initial_terrain();
  return bin_particles(p, t.nx, t.ny, t.cell, particle_spacing(), volume_quantum());
}

double SphModel::step() {
  if (std::any_of(painted_.begin(), painted_.end(), [](const RainDisc& d) { return d.rate < 0; }))
    drain_sinks();
  const double before = sim_->time();
  sim_->step();
  return sim_->time() - before;
}

double SphModel::rain_volume() {
  const double spacing = sim_->solver().settings().spacing;
  return static_cast<double>(sim_->rain().spawned()) * spacing * spacing * spacing;
}

std::optional<WaterBudget> SphModel::water_budget() {
  const double volume = std::pow(sim_->solver().settings().spacing, 3);
  WaterBudget b;
  b.rain = rain_volume();
  b.outflow = static_cast<double>(sim_->counters().outflow_particles) * volume;
  b.stored = static_cast<double>(sim_->particles()) * volume;
  return b;
}

JsonObject SphModel::diagnostics() {
  const SphCounters c = sim_->counters();
  const WaterResolution w = water_resolution();
  const double volume = std::pow(sim_->solver().settings().spacing, 3);
  const auto spawned = static_cast<double>(sim_->rain().spawned());
  const auto held_back = static_cast<double>(sim_->rain().held_back());
  return JsonObject()
      .add("particles_spawned", static_cast<long long>(sim_->rain().spawned()))
      .add("particles_held_back", static_cast<long long>(sim_->rain().held_back()))
      .add("rain_requested_volume", (spawned + held_back) * volume)
      .add("rain_delivered_volume", spawned * volume)
      .add("particles_alive", static_cast<long long>(sim_->particles()))
      .add("particles_evaporated", c.evaporated_particles)
      .add("particles_outflow", c.outflow_particles)
      .add("below_surface_projections", c.surface_projections)
      .add("collisions", c.collisions)
      .add("water_resolution",
           JsonObject()
               .add("bed_particles", w.bed_particles)
               .add("film_share", w.film_share)
               .add("unresolved_share", w.unresolved_share)
               .add("median_particles_per_footprint", w.median_particles_per_footprint))
      .add("effective", sim_->effective_settings());
}

WaterResolution SphModel::water_resolution() {
  if (resolution_ && resolution_->first == sim_->steps()) return resolution_->second;
  ParticleStore& store = sim_->solver().particles();
  const HostParticles p = store.download();
  const std::vector<float> depth = store.read_field(kDepth);
  const SphSettings& s = sim_->solver().settings();
  const Heightmap terrain = sim_->terrain();
  resolution_.emplace(
      sim_->steps(), runnel::water_resolution({p.f[kX], p.f[kY], p.f[kZ], depth, p.contacts},
                                              terrain, s.spacing * s.spacing * s.spacing,
                                              footprint_radius(s, terrain.cell), s.contact_radius));
  return resolution_->second;
}

std::vector<std::pair<std::string, double>> SphModel::summary_values() {
  const WaterResolution w = water_resolution();
  const std::vector<std::string>& names = model_info().summary_names;
  return {{names[0], w.film_share},
          {names[1], w.unresolved_share},
          {names[2], w.median_particles_per_footprint}};
}

std::string SphModel::rain_caution() {
  const RainEmitter& rain = sim_->rain();
  if (rain.held_back() == 0) return {};
  const RainSettings& r = rain.settings();
  const double requested = static_cast<double>(rain.spawned() + rain.held_back());
  const double storm = r.most_alive();
  char line[400];
  std::snprintf(line, sizeof line,
                "rain.max_particles = %lld held back %.0f of the %.0f drops the rain asked for "
                "(%.1f %% of its water; metrics.json: rain_requested_volume, "
                "rain_delivered_volume); rain.max_particles = %.0f (the rate times the longest "
                "lifespan) would deliver it all%s",
                static_cast<long long>(r.max_particles), static_cast<double>(rain.held_back()),
                requested, 100.0 * static_cast<double>(rain.held_back()) / requested, storm,
                r.budget_follows_storm ? ", but does not fit in the device's memory" : "");
  return line;
}

std::string SphModel::scale_caution() const {
  const double dx = particle_spacing();
  const Heightmap& t = sim_->initial_terrain();
  const double relief = static_cast<double>(t.max_height() - t.min_height());
  const double per_minute = scenario_rain_.enabled ? scenario_rain_.rate * 60.0 : 0.0;
  char line[400];
  if (scenario_rain_.enabled && per_minute < kFewestDropsPerMinute) {
    // The rate in drops scales as dx⁻³: the spacing at which the storm gives the fewest.
    const double fix = dx * std::cbrt(std::max(per_minute, 1e-12) / kFewestDropsPerMinute);
    std::snprintf(line, sizeof line,
                  "the rain is %.3g drops a minute of %.3g m³ each at sph.spacing = %.3g m, too "
                  "few to form a flow that can erode; set sph.spacing to %.3g m or less",
                  per_minute, dx * dx * dx, dx, fix);
    return line;
  }
  if (relief > 0 && dx > kMostSpacingPerRelief * relief) {
    std::snprintf(line, sizeof line,
                  "particles of %.3g m are larger than the terrain's relief of %.3g m allows (a "
                  "quarter of it): the water cannot follow its slopes; set sph.spacing to %.3g m "
                  "or less",
                  dx, relief, kMostSpacingPerRelief * relief);
    return line;
  }
  return {};
}

std::string SphModel::caution() {
  std::string rain = rain_caution();
  if (const std::string scale = scale_caution(); !scale.empty())
    rain = rain.empty() ? scale : rain + "; " + scale;
  const WaterResolution w = water_resolution();
  if (w.unresolved_share <= kUnresolvedShareWarning) return rain;
  char line[320];
  std::snprintf(line, sizeof line,
                "%.0f %% of the particles on the bed are drops on their own (even the widest "
                "footprint holds fewer than %.0f other particles' water): erosion there depends "
                "on the particle size. Halve sph.spacing to check, or rain longer "
                "(docs/erosion.md, \"Films\")",
                100.0 * w.unresolved_share, kFilmNeighbours);
  return rain.empty() ? std::string(line) : rain + "; " + line;
}

std::string SphModel::status() {
  return std::to_string(sim_->particles()) + " particles";
}

}  // namespace runnel
