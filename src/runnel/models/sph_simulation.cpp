// SPDX-License-Identifier: MIT
#include "runnel/models/sph_simulation.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/clock.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameters_toml.hpp"
#include "runnel/core/text.hpp"
#include "runnel/core/version.hpp"
#include "runnel/ground/ground_settings.hpp"
#include "runnel/models/model.hpp"
#include "runnel/sph/standing_water_particles.hpp"
#include "runnel/terrain/standing_water.hpp"

namespace runnel {
namespace {

// Heights rounded to the quantum, as the device keeps them.
std::vector<std::int64_t> to_fixed(const Heightmap& t, double quantum) {
  std::vector<std::int64_t> f(t.size());
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = std::llround(t.start_height(k) / quantum);
  return f;
}

}  // namespace

Simulation::Simulation(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : compute_(compute), params_(params), initial_(terrain) {
  // Measured (docs/sph.md): with the default rain, terrains of 10 x 10 vertices and fewer flood
  // their few cells, and the spray over the open edges thins below sph.density_min; 11 x 11 ran
  // on every generator tried. 16 x 16 leaves a margin.
  if (terrain.nx < kMinSphVertices || terrain.ny < kMinSphVertices) {
    throw input_error("terrain: " + std::to_string(terrain.nx) + " x " +
                      std::to_string(terrain.ny) + " vertices is too small for the SPH model (at " +
                      "least " + std::to_string(kMinSphVertices) + " x " +
                      std::to_string(kMinSphVertices) + "; the grid models run on any terrain)");
  }
  const double spacing = runnel::particle_spacing(params, terrain.cell);
  const double relief =
      std::max(0.0, static_cast<double>(terrain.max_height() - terrain.min_height()));
  const double spawn = RainSettings::spawn_height_of(params, spacing);
  const double gravity = params.real("sph.gravity");
  // The speed the water typically reaches: a fall from the spawn height, or a slide down a quarter
  // of the relief (faster water is rarer and tolerates the larger density error).
  reference_speed_ = std::sqrt(2.0 * std::max(gravity, 1e-3) * std::max(0.25 * relief, spawn));
  const SphSettings sph = SphSettings::from(params, spacing, reference_speed_);

  const ErosionSettings erosion = ErosionSettings::from(params, sph, terrain.cell);
  // Standing water at t = 0: its depth per vertex, and the highest water surface.
  const std::vector<float> standing =
      has_standing_water(params) ? initial_water_depth(params, terrain) : std::vector<float>();
  double water_top = terrain.max_height();
  for (std::size_t v = 0; v < standing.size(); ++v)
    water_top = std::max(water_top, static_cast<double>(terrain.h[v] + standing[v]));
  const double top = std::max(terrain.max_height() + spawn, water_top) + 4.0 * spacing;
  // The fluid's hash grid spans the relief and the spawn height in cells of 2h, at most 1024.
  const double most = 1000.0 * 2.0 * sph.h - relief - 4.0 * spacing - 4.0 * sph.h;
  if (spawn > relief && spawn > most) {
    throw input_error("rain.spawn_height: " + format_number(spawn) +
                      " m above the terrain needs more than the fluid grid's 1024 cells of 2h = " +
                      format_number(2.0 * sph.h) + " m; at most " +
                      format_number(std::max(0.0, most)) + " m at this sph.spacing");
  }
  solver_ = std::make_unique<SphSolver>(compute, sph, terrain, top, erosion.height_quantum);
  initial_fixed_ = to_fixed(terrain, erosion.height_quantum);
  // The initial terrain as the run sees it: rounded to the quantum.
  for (std::size_t k = 0; k < initial_.size(); ++k) {
    initial_.h[k] =
        static_cast<float>(static_cast<double>(initial_fixed_[k]) * erosion.height_quantum);
  }
  RainSettings rain = RainSettings::from(params, solver_->terrain(), spacing, reference_speed_);
  rain_mask_ = RainMask(params, terrain.nx, terrain.ny);
  rain_ = std::make_unique<RainEmitter>(
      compute, rain, static_cast<std::uint64_t>(params.integer("run.seed")),
      static_cast<float>(sph.rho0), rain_mask_.weights(), terrain.nx);
  ground_ = make_ground(compute, params, solver_->terrain(), initial_, initial_fixed_);
  // With an exchange interval the water depth is measured only for the exchanges' steps.
  solver_->measure_depth_every(erosion.exchange_interval);
  solver_->keep_water_field_current(rain.above_water);
  erosion_ = std::make_unique<Erosion>(compute, erosion, *solver_,
                                       static_cast<std::uint64_t>(params.integer("run.seed")),
                                       ground_ ? &ground_->bed() : nullptr);
  const ThermalSettings thermal = ThermalSettings::from(params);
  thermal_interval_ = thermal.interval;
  HostParticles body;
  if (!standing.empty()) body = standing_water_particles(sph, initial_, standing);
  initial_water_volume_ = static_cast<double>(body.size()) * spacing * spacing * spacing;
  budget_device_memory(compute, terrain, rain, body.size());
  if (body.size() > 0) solver_->add(std::move(body));
  if (thermal_interval_ > 0) {
    thermal_ = std::make_unique<ThermalRelaxation>(compute, solver_->terrain(), thermal,
                                                   ground_ ? &ground_->bed() : nullptr);
  }
}

// The most device memory the run will hold: the particle store at its largest (the budget with
// the store's growth margin; with dfsph, each particle's neighbour list and pair gradients too),
// the terrain (fixed point, deltas, float view, normals, contact heights, water depth with its
// coarser levels for films, a third more, talus outflows) and the hash grid's cell ranges. Refused
// now, with the figures, rather than failing when the rain has filled the store.
void Simulation::budget_device_memory(const ComputeContext& compute, const Heightmap& terrain,
                                      RainSettings& rain, std::size_t standing_particles) {
  const double vertices = static_cast<double>(terrain.size());
  const std::size_t bytes_each = solver_->bytes_per_particle() + 4;
  const double particle_bytes = 1.5 * static_cast<double>(bytes_each);
  const double fixed_bytes = vertices * (36 + 8 * 4.0 / 3.0 + (thermal_interval_ > 0 ? 32 : 0)) +
                             8.0 * static_cast<double>(solver_->hash().grid().cell_count()) +
                             static_cast<double>(standing_particles) * particle_bytes;
  const double available = static_cast<double>(compute.info().global_memory);
  // A budget that follows the storm stays within the device's memory (the drops beyond are held
  // back, counted and cautioned about); a budget the user set is refused if it does not fit.
  if (rain.budget_follows_storm && available > 0) {
    const double fit = std::floor((available - fixed_bytes) / particle_bytes);
    if (fit >= 1 && static_cast<double>(rain.max_particles) > fit) {
      rain.max_particles = static_cast<std::int64_t>(fit);
      rain_->settings() = rain;
    }
  }
  // No more particles live at once than the budget, nor than the rain spawns over the longest
  // lifespan (the budget may be set far above what the rain can fill).
  const double most_alive = std::min(static_cast<double>(rain.max_particles), rain.most_alive());
  device_bytes_ = most_alive * particle_bytes + fixed_bytes;
  if (available > 0 && device_bytes_ > available) {
    throw input_error("rain.max_particles: the run needs " + format_number(device_bytes_ / 1e6) +
                      " MB of device memory (" + format_number(most_alive) +
                      " particles alive at most, at " + std::to_string(bytes_each) +
                      " bytes each, with growth margin, plus the terrain); " + compute.info().name +
                      " has " + format_number(available / 1e6) + " MB");
  }
}

void Simulation::step() {
  SphSolver& s = *solver_;
  s.drift();  // integrate.kick, sph.continuity, integrate.drift (+ collide.terrain, outflow)
  // erode.exchange and evaporation → fixed-point deltas: every step, or every exchange interval.
  const double exchange_time = erosion_->exchange_time(s.time(), s.dt());
  if (exchange_time > 0) erosion_->exchange(s, exchange_time);
  // thermal.relax, whenever the clock crosses a multiple of the interval (seconds, not steps).
  const bool relax = thermal_ && interval_credit(thermal_interval_, s.time(), s.dt()) > 0;
  if (exchange_time > 0 || relax) {
    s.terrain().apply_changed();  // terrain.apply: deltas → heights, normals (the tiles touched)
    if (relax) thermal_->relax();
    if (ground_) ground_->update();  // the step's net change into the layer stack
    s.project_to_surface();          // no particle stays below a terrain that rose
  }
  rain_->emit(s, s.dt());  // rain.emit: this step's drops at the spawn height
  s.complete_step();       // hash, water depth, sph_forces, kick, next dt
}

MassBalance Simulation::mass_balance() {
  long long suspended = 0;
  ParticleStore& store = solver_->particles();
  if (store.size() > 0) {
    std::vector<std::int32_t> sediment(store.size());
    compute_.queue().enqueueReadBuffer(store.buffer(kSediment), CL_TRUE, 0, sediment.size() * 4,
                                       sediment.data());
    for (auto s : sediment) suspended += s;
  }
  const SphCounters c = solver_->counters();
  return mass_balance_of(initial_fixed_, solver_->terrain().download_fixed(), suspended,
                         c.outflow_sediment, c.lost_sediment, solver_->terrain().volume_quantum(),
                         0, {}, imposed_);
}

std::vector<double> Simulation::elevation() {
  return heights_in_metres(solver_->terrain());
}

void Simulation::set_elevation(const std::vector<double>& metres) {
  imposed_.impose(solver_->terrain(), metres, ground_ != nullptr);
  solver_->terrain_replaced();
}

double Simulation::rain_rate() const {
  const RainSettings& rain = rain_->scenario_rain();
  const double terrain_area = solver_->terrain().extent_x() * solver_->terrain().extent_z();
  return rain.intensity_mm_h / 3.6e6 * rain.area / terrain_area;
}

void Simulation::set_rain_rates(const std::vector<float>& metres_per_second) {
  rain_mask_.set(rain_weights_for(metres_per_second, rain_rate(), initial_.h.size(), "sph"));
  rain_->set_weights(rain_mask_.weights(), initial_.nx);
}

Heightmap Simulation::erosion_reference() const {
  Heightmap reference = initial_;
  imposed_.raise(reference, solver_->terrain().quantum());
  return reference;
}

CheckpointData Simulation::checkpoint() {
  CheckpointData d;
  d.runnel_version = kVersion;
  d.source_revision = kRevision;
  d.parameters_toml = parameters_toml(params_);
  d.terrain = terrain();
  d.height_quantum = solver_->terrain().quantum();
  d.height_fixed = solver_->terrain().download_fixed();
  d.initial_fixed = initial_fixed_;
  ParticleStore& store = solver_->particles();
  d.particles = store.download();
  d.ax = store.read_field(kAx);
  d.ay = store.read_field(kAy);
  d.az = store.read_field(kAz);
  d.drho = store.read_field(kDrho);
  d.depth = store.read_field(kDepth);
  for (ParticleField field : solver_->pressure_solver().kept_fields())
    d.solver_state[field] = store.read_field(field);
  d.next_id = store.next_id();
  d.time = solver_->time();
  d.dt = solver_->dt();
  d.steps = solver_->steps();
  d.rain_spawned = rain_->spawned();
  d.rain_carry = rain_->carry();
  d.rain_held_back = rain_->held_back();
  d.seed = params_.integer("run.seed");
  d.counters = solver_->counters();
  if (ground_) d.fields = ground_->fields();
  rain_mask_.store(d.fields);
  imposed_.store(d.fields);
  return d;
}

void Simulation::restore(const CheckpointData& d) {
  if (d.terrain.nx != initial_.nx || d.terrain.ny != initial_.ny) {
    throw input_error("checkpoint: terrain size does not match the simulation");
  }
  initial_fixed_ = d.initial_fixed;
  for (std::size_t k = 0; k < initial_.size(); ++k) {
    initial_.h[k] = static_cast<float>(static_cast<double>(initial_fixed_[k]) * d.height_quantum);
  }
  solver_->terrain().upload_fixed(d.height_fixed);
  ParticleStore& store = solver_->particles();
  store.upload(d.particles);
  store.upload_field(kAx, d.ax);
  store.upload_field(kAy, d.ay);
  store.upload_field(kAz, d.az);
  store.upload_field(kDrho, d.drho);
  store.upload_field(kDepth, d.depth);
  for (ParticleField field : solver_->pressure_solver().kept_fields()) {
    // A checkpoint of another solver has none: the solves then start cold.
    const auto kept = d.solver_state.find(field);
    store.upload_field(field, kept != d.solver_state.end()
                                  ? kept->second
                                  : std::vector<float>(d.particles.size(), 0.0f));
  }
  store.set_next_id(d.next_id);
  solver_->restore_clock(d.time, d.dt, d.steps);
  solver_->restore_counters(d.counters);
  rain_->restore(d.rain_spawned, d.rain_carry, d.rain_held_back);
  if (ground_) ground_->restore(d.fields);
  rain_mask_.restore(d.fields);
  if (rain_mask_.present()) rain_->set_weights(rain_mask_.weights(), initial_.nx);
  imposed_.restore(d.fields);
}

bool Simulation::paint_rain_mask(const std::vector<int>& vertices, float value) {
  if (!rain_mask_.present()) return false;
  rain_mask_.paint(vertices, value);
  rain_->set_weights(rain_mask_.weights(), initial_.nx);
  return true;
}

Heightmap Simulation::terrain() {
  Heightmap t = solver_->terrain().download();
  t.origin_x = initial_.origin_x;
  t.origin_z = initial_.origin_z;
  t.georef = initial_.georef;
  return t;
}

JsonObject Simulation::effective_settings() const {
  const SphSettings& s = solver_->settings();
  return JsonObject()
      .add("spacing_m", s.spacing)
      .add("smoothing_length_m", s.h)
      .add("c0_m_per_s", s.c0)
      .add("reference_speed_m_per_s", reference_speed_)
      .add("particle_volume_m3", s.spacing * s.spacing * s.spacing)
      .add("solver", solver_->solver_json())
      .add("rain", rain_->settings().json())
      .add("erosion", erosion_->settings().json());
}

}  // namespace runnel
