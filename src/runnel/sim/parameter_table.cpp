// SPDX-License-Identifier: MIT
// The parameter table: every scenario key of runnel, with its default, unit, range and meaning.
#include "runnel/sim/parameters.hpp"

namespace runnel {

const std::vector<ParamSpec>& parameter_table() {
  using T = ParamType;
  static const std::vector<ParamSpec> table = {
      // clang-format off
      // terrain: where the heightmap comes from
      {"terrain.file", T::kString, "\"\"", "", 0, 0, {}, "terrain file (.asc, .png, .npy), relative to the scenario file; empty: use terrain.generator"},
      {"terrain.generator", T::kString, "\"fbm\"", "", 0, 0, {"diamond-square", "fault", "fbm", "ridged", "crooked", "pyramid", "hemisphere", "plane", "cone", "v-valley"}, "generator used when terrain.file is empty; its own parameters go in [terrain.set]"},
      {"terrain.size", T::kInteger, "257", "vertices", 2, 32768, {}, "generated terrain: vertices per side"},
      {"terrain.cell", T::kReal, "1.0", "m", 1e-6, 1e6, {}, "cell size (vertex spacing); for files, overrides the file's own when terrain.cell_from_file is false"},
      {"terrain.cell_from_file", T::kBool, "true", "", 0, 0, {}, "take the cell size from the terrain file when it has one (ASC, runnel PNG)"},
      {"terrain.seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "generator seed"},
      {"terrain.nodata", T::kString, "\"fill\"", "", 0, 0, {"fill", "refuse"}, "NODATA cells in an ASCII grid: fill from neighbours, or refuse the file"},
      // sph: the weakly compressible SPH fluid (physics.md §2)
      {"sph.spacing", T::kReal, "0", "m", 0, 1e4, {}, "particle spacing dx (particle volume dx³); 0: derived from the case (half the terrain's cell size for runs: several particles across a channel)"},
      {"sph.h_factor", T::kReal, "1.2", "1", 0.8, 2.5, {}, "smoothing length h = h_factor · dx (support radius 2h)"},
      {"sph.rho0", T::kReal, "1000", "kg/m^3", 1, 1e5, {}, "rest density ρ0"},
      {"sph.c0", T::kReal, "0", "m/s", 0, 1e5, {}, "speed of sound; 0: 10 × the case's reference speed (free fall from the spawn height, or sqrt(g H))"},
      {"sph.alpha_visc", T::kReal, "0.02", "1", 0, 10, {}, "Monaghan artificial viscosity α"},
      {"sph.delta", T::kReal, "0.1", "1", 0, 1, {}, "δ-SPH density diffusion coefficient (Molteni & Colagrossi 2009)"},
      {"sph.cfl", T::kReal, "0.25", "1", 0.01, 0.5, {}, "time step factor: dt = cfl · min(h/(c0 + |v|max), sqrt(h/|a|max))"},
      {"sph.dt_min", T::kReal, "1e-7", "s", 1e-12, 1, {}, "smallest time step: reaching it stops the run as unstable"},
      {"sph.dt_max", T::kReal, "0.01", "s", 1e-9, 10, {}, "largest time step"},
      {"sph.gravity", T::kReal, "9.81", "m/s^2", 0, 100, {}, "gravitational acceleration (along −y)"},
      {"sph.clamp_negative_pressure", T::kBool, "true", "", 0, 0, {}, "clamp negative pressure to 0 (free-surface rain: no tensile attraction between droplets)"},
      {"sph.walls", T::kBool, "false", "", 0, 0, {}, "vertical walls at the domain edges; false: open edges, particles that leave are removed as outflow"},
      {"sph.restitution", T::kReal, "0", "1", 0, 1, {}, "restitution e of the terrain and wall contact"},
      {"sph.manning_n", T::kReal, "0.03", "s/m^(1/3)", 0, 1, {}, "Manning's roughness n of the terrain: bed shear stress ρ g n² |u|²/D^(1/3) on particles touching it (D the local flow depth); 0: frictionless"},
      {"sph.contact_radius", T::kReal, "0.5", "dx", 0, 2, {}, "particle radius for the terrain contact: a resting particle's centre sits this far above the terrain along the normal (0.5: the particle of volume dx³ rests on its lowest point)"},
      {"sph.surface_eps", T::kReal, "0.01", "dx", 0, 0.5, {}, "ε, how far above the contact surface a particle is put after a hit"},
      {"sph.density_min", T::kReal, "0.1", "1", 0.001, 1, {}, "smallest sane density as a fraction of ρ0: below it the run stops (rain drops that leave the ground expand; with clamped pressure that is harmless)"},
      {"sph.density_max", T::kReal, "1.5", "1", 1, 100, {}, "largest sane density as a fraction of ρ0: above it the run stops"},
      // rain: the emitter (physics.md §4)
      {"rain.region", T::kString, "\"terrain\"", "", 0, 0, {"terrain", "rectangle", "disc"}, "where rain falls: the whole terrain, rain.rect_*, or the disc rain.disc_*"},
      {"rain.rect_x0", T::kReal, "0", "m", -1e9, 1e9, {}, "rectangle: west edge (x)"},
      {"rain.rect_x1", T::kReal, "0", "m", -1e9, 1e9, {}, "rectangle: east edge (x)"},
      {"rain.rect_z0", T::kReal, "0", "m", -1e9, 1e9, {}, "rectangle: north edge (z)"},
      {"rain.rect_z1", T::kReal, "0", "m", -1e9, 1e9, {}, "rectangle: south edge (z)"},
      {"rain.disc_x", T::kReal, "0", "m", -1e9, 1e9, {}, "disc: centre x"},
      {"rain.disc_z", T::kReal, "0", "m", -1e9, 1e9, {}, "disc: centre z"},
      {"rain.disc_radius", T::kReal, "0", "m", 0, 1e9, {}, "disc: radius"},
      {"rain.rate", T::kReal, "0", "particles/s", 0, 1e9, {}, "particles spawned per second; 0: from rain.intensity, or if that is 0 too, max_particles / lifespan"},
      {"rain.intensity", T::kReal, "0", "mm/h", 0, 1e9, {}, "rain intensity over the region (converted through the particle volume dx³); used when rain.rate is 0"},
      {"rain.spawn_height", T::kReal, "0", "m", 0, 1e6, {}, "height above the terrain where drops appear; 0: 1 dx"},
      {"rain.speed", T::kReal, "0", "m/s", 0, 1e4, {}, "initial downward speed of a drop"},
      {"rain.max_particles", T::kInteger, "20000", "particles", 0, 1e8, {}, "particle budget: the emitter never lets more particles live at once"},
      {"rain.lifespan", T::kReal, "0", "s", 0, 1e9, {}, "mean lifespan of a drop before it evaporates; 0: the time to cross the terrain at a tenth of the reference speed (water under bed friction runs slower than a free fall)"},
      {"rain.lifespan_jitter", T::kReal, "0.25", "1", 0, 0.99, {}, "lifespans are uniform in mean·(1 ± jitter)"},
      {"rain.enabled", T::kBool, "true", "", 0, 0, {}, "rain on or off"},
      // erosion: dissolving and depositing sediment (physics.md §4)
      {"erosion.model", T::kString, "\"stream-power\"", "", 0, 0, {"stream-power", "acidity"}, "stream-power: detachment driven by the power the flow spends on its bed against a transport capacity, coupled as Foster & Meyer 1975 (docs/erosion.md); acidity: Fritz 2016's fixed erosion per contact"},
      {"erosion.erodibility", T::kReal, "0.001", "s^2/m^2", 0, 1e6, {}, "K_ω: detachment K_ω (ω − ω_c) in kg/m²/s, ω the stream power on the bed in W/m²"},
      {"erosion.critical_power", T::kReal, "0", "W/m^2", 0, 1e9, {}, "ω_c, the stream power below which the flow detaches nothing"},
      {"erosion.transport_efficiency", T::kReal, "0.02", "s^2/m", 0, 1e6, {}, "k_T: transport capacity k_T ω per unit width (kg/m/s, ω the stream power; Bagnold 1966: about 0.16 × his efficiency, 0.01–0.15), carried as the concentration k_T ρ0 g S / ρ_b (S the sine of the slope)"},
      {"erosion.settling_velocity", T::kReal, "0.01", "m/s", 0, 100, {}, "w_s, the fall velocity of the sediment (fine sand about 0.01): deposition w_s (c − c_T)"},
      {"erosion.bed_density", T::kReal, "1600", "kg/m^3", 1, 1e5, {}, "ρ_b, dry bulk density of the bed: converts mass rates into bed volume"},
      {"erosion.max_concentration", T::kReal, "0.2", "1", 0, 1, {}, "c_max, the most bed volume a particle carries per volume of its water"},
      {"erosion.morphological_factor", T::kReal, "1", "1", 0, 1e9, {}, "morphological acceleration (Roelvink 2006): the bed changes as over this many seconds for each second of flow; detachment, transport capacity and the load limit scale with it, the water does not"},
      {"erosion.acidity", T::kReal, "0.001", "m", 0, 1e3, {}, "acidity model: depth eroded per contact (× cell²)"},
      {"erosion.capacity_contacts", T::kInteger, "10", "1", 0, 1e9, {}, "acidity model: erosion events per particle"},
      {"erosion.deposit_fraction", T::kReal, "1", "1", 0, 1, {}, "share of the load deposited on evaporation; < 1 reproduces Fritz 2016 and books the rest as lost (non-conserving)"},
      {"erosion.height_quantum", T::kReal, "1e-6", "m", 1e-12, 1, {}, "fixed-point quantum of terrain heights; sediment is counted in quantum · cell²"},
      // thermal: talus relaxation during a run
      {"thermal.interval", T::kReal, "0.5", "s", 0, 1e9, {}, "SPH runs: relax slopes steeper than the talus angle every this many simulated seconds; 0: off"},
      {"thermal.talus_angle", T::kReal, "40", "deg", 0, 89, {}, "talus angle"},
      {"thermal.rate", T::kReal, "0.5", "1", 0, 1, {}, "c, the fraction of the excess moved per relaxation"},
      {"thermal.height_aware", T::kBool, "false", "", 0, 0, {}, "height-aware talus (Fritz 2016): the threshold rises with height, keeping peaks sharp"},
      {"thermal.hardness", T::kReal, "1", "1", 0, 100, {}, "height-aware: threshold × (1 + hardness · normalised height)"},
      // droplet: Beyer 2015's particle droplets (models.md), in cells and metres of height
      {"droplet.radius", T::kReal, "3", "cells", 0.5, 8, {}, "erosion brush radius (its weights are kept in private memory: at most 8)"},
      {"droplet.inertia", T::kReal, "0.05", "1", 0, 1, {}, "how much a droplet keeps its direction"},
      {"droplet.capacity", T::kReal, "4", "1", 0, 1e6, {}, "capacity factor: capacity = −Δh · speed · water · factor"},
      {"droplet.min_capacity", T::kReal, "0.01", "m", 0, 1e6, {}, "smallest capacity"},
      {"droplet.erode", T::kReal, "0.3", "1", 0, 1, {}, "fraction of the free capacity eroded per step"},
      {"droplet.deposit", T::kReal, "0.3", "1", 0, 1, {}, "fraction of the excess load deposited per step"},
      {"droplet.evaporate", T::kReal, "0.01", "1", 0, 1, {}, "fraction of the water evaporating per step"},
      {"droplet.gravity", T::kReal, "4", "1", 0, 1e3, {}, "gravity of the speed update"},
      {"droplet.lifetime", T::kInteger, "30", "steps", 1, 100000, {}, "steps a droplet lives"},
      {"droplet.initial_water", T::kReal, "1", "1", 0, 1e6, {}, "water a droplet starts with"},
      {"droplet.initial_speed", T::kReal, "1", "1", 0, 1e6, {}, "speed a droplet starts with"},
      {"droplet.batch", T::kInteger, "0", "droplets", 0, 1e8, {}, "droplets per parallel batch (they see the terrain as at the batch start); 0: one per 64 cells, so few share a pit"},
      {"droplet.volume", T::kReal, "0", "m^3", 0, 1e9, {}, "rain water one droplet stands for (rain_volume in metrics; runnel compare sets it to the SPH particle volume); 0: cell³"},
      // olsen: cellular-automaton hydraulic erosion (Olsen 2004), per iteration
      {"olsen.rain", T::kReal, "0.01", "m", 0, 1e3, {}, "K_r, water added to every cell per iteration"},
      {"olsen.solubility", T::kReal, "0.01", "1", 0, 1, {}, "K_s, terrain dissolved per unit water depth"},
      {"olsen.evaporation", T::kReal, "0.5", "1", 0, 1, {}, "K_e, fraction of the water evaporating per iteration"},
      {"olsen.capacity", T::kReal, "0.01", "1", 0, 1e3, {}, "K_c, sediment capacity per unit water depth"},
      // pipe: virtual-pipe shallow water with erosion (Mei, Decaudin, Hu 2007)
      {"pipe.rain", T::kReal, "0.01", "m/s", 0, 1e3, {}, "rain on every cell"},
      {"pipe.area", T::kReal, "1", "m^2", 1e-6, 1e6, {}, "A, cross-section of the virtual pipes"},
      {"pipe.gravity", T::kReal, "9.81", "m/s^2", 0, 100, {}, "gravity"},
      {"pipe.capacity", T::kReal, "0.05", "s", 0, 1e6, {}, "K_c: capacity = K_c · max(sin α, min_tilt) · |v| (m of height)"},
      {"pipe.dissolve", T::kReal, "100", "1/s", 0, 1e6, {}, "K_s, rate at which the free capacity is dissolved: (1 − exp(−K_s·Δt))(C − s) per step"},
      {"pipe.deposit", T::kReal, "100", "1/s", 0, 1e6, {}, "K_d, rate at which the excess load is deposited: (1 − exp(−K_d·Δt))(s − C) per step"},
      {"pipe.evaporation", T::kReal, "0.05", "1/s", 0, 1e3, {}, "K_e, evaporation rate"},
      {"pipe.manning_n", T::kReal, "0.03", "s/m^(1/3)", 0, 1, {}, "Manning's n of the bed friction on the pipe flow (the SPH model's law; not in Mei 2007): without it thin films run as fast as the flux limiter lets them, whatever the time step; 0: Mei's frictionless pipes"},
      {"pipe.min_tilt", T::kReal, "0.05", "1", 0, 1, {}, "smallest sin α in the capacity"},
      {"pipe.cfl", T::kReal, "0.25", "1", 0.01, 1, {}, "Δt ≤ cfl · l / (sqrt(g d_max) + |v|_max)"},
      {"pipe.cfl_depth", T::kReal, "0.01", "m", 0, 1e3, {}, "water thinner than this does not count in the CFL limit (a thin film's flux over its depth is not a wave speed; the flux limit keeps it non-negative)"},
      {"pipe.dt_min", T::kReal, "1e-6", "s", 0, 100, {}, "smallest time step: a step the CFL limit would make shorter stops the run with an error (a collapsing step means the flow has blown up)"},
      {"pipe.dt_max", T::kReal, "0.05", "s", 1e-9, 100, {}, "largest time step"},
      {"pipe.transport", T::kString, "\"upwind\"", "", 0, 0, {"upwind", "semi-lagrangian"}, "sediment transport: upwind (mass-conserving, sediment leaves with the water) or semi-lagrangian (Mei 2007's advection; not conserving, the loss is reported as lost_volume)"},
      {"pipe.edges", T::kString, "\"outflow\"", "", 0, 0, {"outflow", "closed"}, "outflow (outside cells have b = d = 0) or closed"},
      // run: the simulation as a whole
      {"run.model", T::kString, "\"sph\"", "", 0, 0, {"sph", "droplet", "pipe", "olsen", "thermal"}, "erosion model (docs/models.md): sph (runnel's own), droplet (Beyer 2015), pipe (Mei 2007), olsen (Olsen 2004), thermal (talus)"},
      {"run.seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "seed of the simulation's random numbers (rain)"},
      {"run.steps", T::kInteger, "0", "steps", 0, 1e12, {}, "steps to run; 0: run for run.sim_time"},
      {"run.sim_time", T::kReal, "10", "s", 0, 1e12, {}, "simulated time to run when run.steps is 0 (models with a clock in seconds: sph, pipe)"},
      {"run.iterations", T::kInteger, "100", "iterations", 0, 1e12, {}, "iterations to run when run.steps is 0 (models counting iterations: droplet batches, olsen, thermal)"},
      {"run.report_every", T::kInteger, "200", "steps", 1, 1e12, {}, "steps between mass-balance reports (progress lines when not on a terminal)"},
      // clang-format on
  };
  return table;
}

}  // namespace runnel
