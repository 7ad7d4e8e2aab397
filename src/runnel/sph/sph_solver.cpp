// SPDX-License-Identifier: MIT
#include "runnel/sph/sph_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/clock.hpp"
#include "runnel/core/error.hpp"
#include "runnel/sph/pressure/registry.hpp"
#include "runnel/sph/water_depth_reference.hpp"

namespace runnel {
namespace {

const std::vector<std::string> kSphSources = {
    "cl/common.cl",         "cl/counters.cl",     "cl/grid.cl",      "cl/sph_kernel.cl",
    "cl/terrain_sample.cl", "cl/sph_boundary.cl", "cl/collide.cl",   "cl/sph_forces.cl",
    "cl/sph_continuity.cl", "cl/integrate.cl",    "cl/footprint.cl", "cl/water_depth.cl",
    "cl/dfsph_density.cl",  "cl/dfsph_solve.cl"};
constexpr int kStatColumns = 6;
// step_stats' rows: on a CPU at most 256 contiguous runs; on a GPU at most 16384 interleaved ones
// of at least 64 particles (a thread per row, and rows enough to keep the GPU busy).
constexpr cl_uint kStatBlocksCpu = 256, kStatBlocksGpu = 16384, kStatLeastRunGpu = 64;

// Particles a work-item of water_depth_scatter_runs counts (cl/water_depth.cl), and the particles
// per tile of the hash from which the solver takes that kernel: a sheet of water has about one
// particle to a tile, whose footprints seldom overlap, a deep pool 8 to 27.
constexpr unsigned kWaterRun = 16;
constexpr unsigned kDeepWaterPerTile = 4;
// Work-items of a water_depth_coarsen group (a block's first level has up to 32 × 32 vertices).
constexpr std::size_t kCoarsenGroup = 64;

// The footprint and the particle volume for the water depth pass (cl/water_depth.cl).
std::string footprint_options(const SphSettings& s, double terrain_cell) {
  const double radius = footprint_radius(s, terrain_cell);
  // The most vertices a footprint spans along an axis: floor(2R/cell) + 1, and one more for the
  // float rounding of its ends.
  const int side = static_cast<int>(std::floor(2.0 * radius / terrain_cell)) + 2;
  return float_define("FOOTPRINT_RADIUS", radius) + " -DFOOTPRINT_SIDE=" + std::to_string(side) +
         float_define("WATER_PARTICLE_VOLUME", s.spacing * s.spacing * s.spacing) +
         " -DWATER_RUN=" + std::to_string(kWaterRun) + "u" +

         float_define("FILM_NEIGHBOURS", kFilmNeighbours) +
         " -DFILM_LEVELS_MAX=" + std::to_string(kFilmLevelsMax);
}

// Candidates a tiled neighbour pass holds in local memory at once: as many as half the device's
// local memory takes at 64 bytes each (the passes keep up to 12 four-byte values per candidate),
// in multiples of 64, between 64 and 512 (a tile's neighbourhood is about 400 candidates).
std::size_t candidate_chunk(ComputeContext& compute) {
  const std::size_t fits = compute.info().local_memory / 2 / 64 / 64 * 64;
  return std::clamp<std::size_t>(fits, 64, 512);
}

GridSpec fluid_grid(const SphSettings& s, const Heightmap& floor, double top) {
  const double margin = 2.0 * s.h;
  const double lo[3] = {-margin, floor.min_height() - margin, -margin};
  const double hi[3] = {(floor.nx - 1) * floor.cell + margin,
                        std::max(top, floor.max_height() + margin),
                        (floor.ny - 1) * floor.cell + margin};
  return GridSpec::covering(lo, hi, 2.0 * s.h);
}

}  // namespace

// The device's own division: on a GPU the correctly rounded one made water_depth_gather five
// times slower and the neighbour passes' square roots and divisions cost (docs/gpu.md), and their
// results are checked against the C++ reference within tolerances.
cl::Program& sph_program(ComputeContext& compute, const SphSettings& settings,
                         double terrain_cell) {
  return compute.program(kSphSources,
                         settings.build_options() + footprint_options(settings, terrain_cell) +
                             " -DSPH_CHUNK=" + std::to_string(candidate_chunk(compute)) +
                             " -DSPH_SKIP_FAR=" + (compute.wide() ? "1" : "0"),
                         ComputeContext::Division::device);
}

SphSolver::SphSolver(ComputeContext& compute, const SphSettings& settings, const Heightmap& floor,
                     double top, double height_quantum)
    : compute_(compute),
      settings_(settings),
      terrain_(compute, floor, height_quantum),
      store_(compute),
      hash_(compute, fluid_grid(settings, floor, top)) {
  // The drift and the projection sample the contact surface (SPH_CONTACT_RADIUS, the same float).
  terrain_.carry_contact_surface(static_cast<float>(settings.contact_radius));
  cl::Program& program = sph_program(compute, settings, floor.cell);
  pressure_ = pressure_method(settings.solver).make(compute, program, settings);
  hash_.carry_fields(pressure_->kept_fields());
  drift_ = Kernel(compute, program, "drift");
  friction_factors_ = Kernel(compute, program, "bed_friction_factors");
  stats_ = Kernel(compute, program, "step_stats");
  project_ = Kernel(compute, program, "project_to_surface");
  depth_scatter_ = Kernel(compute, program, "water_depth_scatter");
  depth_scatter_runs_ = Kernel(compute, program, "water_depth_scatter_runs");
  depth_gather_ = Kernel(compute, program, "water_depth_gather");
  depth_coarsen_ = Kernel(compute, program, "water_depth_coarsen");
  water_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE,
                      film_level_vertices(floor.nx, floor.ny) * sizeof(cl_long));
  // No water before the first depth pass (the rain emitter may read it first).
  compute.queue().enqueueFillBuffer(water_, cl_long{0}, 0,
                                    film_level_vertices(floor.nx, floor.ny) * sizeof(cl_long));
  stat_blocks_ = compute.wide() ? kStatBlocksGpu : kStatBlocksCpu;
  stats_buffer_ =
      cl::Buffer(compute.context(), CL_MEM_READ_WRITE, stat_blocks_ * kStatColumns * sizeof(float));
  counters_buffer_ =
      cl::Buffer(compute.context(), CL_MEM_READ_WRITE, kCounterCount * sizeof(cl_long));
  const cl_long zero = 0;
  compute.queue().enqueueFillBuffer(counters_buffer_, zero, 0, kCounterCount * sizeof(cl_long));
}

void SphSolver::add(HostParticles particles) {
  if (particles.size() == 0) return;
  store_.append(std::move(particles));
  rates_ready_ = false;
}

void SphSolver::prepare() {
  sort_particles();
  measure_water_depth();
  drop_dead_particles();
  SphPipeline p = pipeline();
  pressure_->measure_rates(p);
  choose_next_dt();
  rates_ready_ = true;
}

// One kick-drift-kick step; reads like the algorithm.
void SphSolver::step() {
  drift();
  complete_step();
}

// v(n+½) = v(n) + a(n)·dt/2 (with whatever impulse the pressure solver adds first), then x(n+1):
// walls, outflow, terrain contact, bed friction; the drift's midpoints and velocities for a
// continuity pass; and the pressure solver makes the new state current.
void SphSolver::drift() {
  if (!rates_ready_) prepare();
  SphPipeline p = pipeline();
  if (hash_stale_) {  // a restored state: same order, cell tables rebuilt
    build_hash();
    // The water field of the restored positions, which the uninterrupted run measured at the
    // last step's end (the particles' depth D came back with them).
    if (water_field_every_step_) scatter_water();
    pressure_->rehashed(p);
  }
  pressure_->before_drift(p, dt_);
  drift_and_collide();
  pressure_->after_drift(p, dt_);
}

// Between the hash's two halves the store still counts the dead particles at its end: both water
// kernels skip them, and the choice between the two takes the last finished build's tiles (they
// give the same field, so the choice changes the time only).
void SphSolver::measure_water_depth() {
  if (!scatter_water()) return;
  const cl_uint n = static_cast<cl_uint>(store_.size());
  const int levels = film_levels(terrain_.nx(), terrain_.ny());
  coarsen_water(levels);
  bind_water_field(depth_gather_);
  store_.bind(depth_gather_, {kDepth});
  depth_gather_.set("levels", levels);
  depth_gather_.launch_lanes(n);
}

void SphSolver::bind_water_field(Kernel& k) {
  store_.bind(k, {kX, kZ, kId});
  k.set("water", water_).set("tnx", terrain_.nx()).set("tny", terrain_.ny());
  k.set("tcell", terrain_.cell());
}

bool SphSolver::scatter_water() {
  const cl_uint n = static_cast<cl_uint>(store_.size());
  const std::size_t vertices = static_cast<std::size_t>(terrain_.nx()) * terrain_.ny();
  compute_.queue().enqueueFillBuffer(water_, cl_long{0}, 0, vertices * sizeof(cl_long));
  if (n == 0) return false;
  // Where the water lies deep, consecutive particles share vertices, and counting them in runs
  // saves most of the atomics on them; a GPU's atomics are cheap, and it needs the work-items.
  const bool in_runs = compute_.info().type != "GPU" && n >= kDeepWaterPerTile * hash_.tile_count();
  Kernel& scatter = in_runs ? depth_scatter_runs_ : depth_scatter_;
  bind_water_field(scatter);
  scatter.launch(round_up_work(in_runs ? (n + kWaterRun - 1) / kWaterRun : n));
  return true;
}

// The water counted on coarser grids for the films' depth (water_depth_reference.hpp), in one
// launch: a work-group per vertex of the coarsest level (cl/water_depth.cl).
void SphSolver::coarsen_water(int levels) {
  if (levels == 0) return;
  const std::size_t blocks = static_cast<std::size_t>(film_level_side(terrain_.nx(), levels)) *
                             film_level_side(terrain_.ny(), levels);
  depth_coarsen_.set("water", water_).set("nx", terrain_.nx()).set("ny", terrain_.ny());
  depth_coarsen_.set("levels", levels).launch_groups(blocks, kCoarsenGroup);
}

void SphSolver::complete_step() {
  sort_particles();  // by cell, dead particles last; cell tables, tiles
  // D at x(n+1), new drops included: the next step's friction and erosion.
  if (depth_interval_ <= 0) {
    measure_water_depth();
  } else if (water_field_every_step_) {
    scatter_water();  // the field alone, for the rain above the water; D stays the exchanges'
  }
  drop_dead_particles();  // the hash's live count and tiles, read while any depth pass runs
  SphPipeline p = pipeline();
  pressure_->complete(p, dt_);  // a(n+1) at x(n+1)
  time_ += dt_;
  ++steps_;
  // v(n+1) = v(n+½) + a(n+1)·dt/2 in the pass that measures the state, unless the pressure solver
  // gave it; then the solver's time-step limits. Stops on NaN or a collapsing step.
  choose_next_dt(pressure_->closing_kick_in_stats());
  // Or D only before a step that will exchange with the bed (its dt is now chosen).
  if (depth_interval_ > 0 && interval_credit(depth_interval_, time_, dt_) > 0)
    measure_water_depth();
}

void SphSolver::measure_depth_every(double seconds) {
  depth_interval_ = seconds;
  hash_.carry_water_depth(seconds > 0);
}

void SphSolver::drift_and_collide() {
  const cl_uint n = static_cast<cl_uint>(store_.size());
  auto& k = drift_;
  store_.bind(
      k, {kX, kY, kZ, kVx, kVy, kVz, kRho, kAge, kSediment, kContacts, kId, kAx, kAy, kAz, kDepth});
  store_.bind_new(k, {kX, kY, kZ});
  bind_continuity_inputs(store_, k);
  launch_bed_friction_factors(store_, friction_factors_, k);
  terrain_.bind_contact(k);
  terrain_.bind_extent(k);
  k.set("dt", static_cast<float>(dt_)).set("counters", counters_buffer_);
  k.launch(round_up_work(n));
}

void SphSolver::build_hash() {
  sort_particles();
  drop_dead_particles();
}

void SphSolver::sort_particles() {
  hash_.begin_build(store_);
  hash_stale_ = false;
}

void SphSolver::drop_dead_particles() {
  hash_.finish_build(store_);
}

void SphSolver::project_to_surface() {
  const cl_uint n = static_cast<cl_uint>(store_.size());
  store_.bind(project_, {kX, kY, kZ, kVx, kVy, kVz, kId});
  terrain_.bind_contact(project_);
  project_.set("counters", counters_buffer_).launch(round_up_work(n));
}

void SphSolver::terrain_replaced() {
  project_to_surface();
  hash_stale_ = true;
}

void bind_continuity_inputs(ParticleStore& store, Kernel& k) {
  const char* inputs[] = {"mid_x", "mid_y", "mid_z", "drift_vx", "drift_vy", "drift_vz", "volume"};
  static_assert(std::size(inputs) <= ParticleStore::kSpareCount);
  for (std::size_t s = 0; s < std::size(inputs); ++s)
    k.set(inputs[s], store.spare(static_cast<int>(s)));
}

void launch_bed_friction_factors(ParticleStore& store, Kernel& factors, Kernel& drift) {
  const cl_uint n = static_cast<cl_uint>(store.size());
  cl::Buffer& factor = store.scratch(kRho);
  store.bind(factors, {kDepth});
  factors.set("n", n).set("factor", factor).launch_lanes(n);
  drift.set("friction", factor);
}

void SphSolver::choose_next_dt(bool closing_kick) {
  const cl_uint n = static_cast<cl_uint>(store_.size());
  health_ = SphHealth{};
  const auto& s = settings_;
  if (n == 0) {  // no fluid yet
    dt_ = pressure_->first_dt();
    return;
  }
  // A CPU: a few contiguous runs; a GPU: thousands of interleaved ones (step_stats in
  // integrate.cl).
  const bool wide = compute_.wide();
  const SerialRuns runs = serial_runs(n, wide ? kStatLeastRunGpu : 1, stat_blocks_);
  const cl_uint blocks = static_cast<cl_uint>(runs.runs), chunk = static_cast<cl_uint>(runs.length);
  store_.bind(stats_, {kVx, kVy, kVz, kAx, kAy, kAz, kRho, kDrho});
  stats_.set("kick", cl_uint{closing_kick}).set("half_dt", static_cast<float>(0.5 * dt_));
  stats_.set("chunk", chunk).set("chunk_stride", wide ? 1 : chunk).set("stride", wide ? blocks : 1);
  stats_.set("blocks", blocks).set("stats", stats_buffer_).launch(round_up_work(blocks));
  // Rows past the particles keep the neutral values (0, 0, ∞, −∞, 0, 0) and are not read.
  const cl_uint used = std::min(blocks, (n + chunk - 1) / chunk);
  stat_rows_.resize(std::size_t{used} * kStatColumns);
  compute_.queue().enqueueReadBuffer(stats_buffer_, CL_TRUE, 0, stat_rows_.size() * sizeof(float),
                                     stat_rows_.data());
  double v2 = 0, a2 = 0, rmin = INFINITY, rmax = -INFINITY, drmax = 0;
  long long bad = 0;
  for (cl_uint b = 0; b < used; ++b) {
    const float* r = stat_rows_.data() + kStatColumns * b;
    v2 = std::max(v2, double(r[0]));
    a2 = std::max(a2, double(r[1]));
    rmin = std::min(rmin, double(r[2]));
    rmax = std::max(rmax, double(r[3]));
    bad += static_cast<long long>(r[4]);
    drmax = std::max(drmax, double(r[5]));
  }
  health_ = {std::sqrt(v2), std::sqrt(a2), rmin, rmax, drmax, bad};
  const std::string where =
      "SPH step " + std::to_string(steps_) + " (t = " + std::to_string(time_) + " s): ";
  if (bad > 0)
    throw runtime_error(where + std::to_string(bad) + " particles have NaN or infinite values");
  // (A summation density is below ρ0 wherever the water thins: only its upper bound is a sign of
  // trouble.)
  const bool too_thin = pressure_->density_floor_checked() && rmin < s.density_min * s.rho0;
  if (too_thin || rmax > s.density_max * s.rho0) {
    std::ostringstream msg;
    msg << where << "density " << (too_thin ? rmin : rmax) << " kg/m^3 is outside the sane range ["
        << s.density_min * s.rho0 << ", " << s.density_max * s.rho0
        << "] (sph.density_min/max): the run is unstable";
    // (Continuity holds the density at the floor, so only a particle added below it, or the
    // compressive side, reach here.)
    throw runtime_error(msg.str());
  }
  dt_ = std::min(pressure_->next_dt(health_), s.dt_max);
  const double dt = dt_;
  if (dt < s.dt_min) {
    std::ostringstream msg;
    msg << where << "time step " << dt << " s fell below sph.dt_min = " << s.dt_min << " s (|v|max "
        << health_.v_max << " m/s, |a|max " << health_.a_max << " m/s^2): the run is unstable";
    throw runtime_error(msg.str());
  }
}

void SphSolver::restore_clock(double time, double dt, std::uint64_t steps) {
  time_ = time;
  dt_ = dt;
  steps_ = steps;
  rates_ready_ = true;  // the restored accelerations belong to the restored state
  hash_stale_ = true;   // but the cell tables must be rebuilt before the next continuity pass
}

SphCounters SphSolver::counters() {
  cl_long c[kCounterCount] = {0};
  compute_.queue().enqueueReadBuffer(counters_buffer_, CL_TRUE, 0, sizeof(c), c);
  return {c[0], c[1], c[2], c[3], c[4], c[5]};
}

void SphSolver::restore_counters(const SphCounters& c) {
  const cl_long values[kCounterCount] = {c.surface_projections,  c.outflow_particles,
                                         c.collisions,           c.outflow_sediment,
                                         c.evaporated_particles, c.lost_sediment};
  compute_.queue().enqueueWriteBuffer(counters_buffer_, CL_TRUE, 0, sizeof(values), values);
}

}  // namespace runnel
