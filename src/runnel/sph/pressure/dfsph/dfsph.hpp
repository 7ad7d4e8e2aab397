// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <utility>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/pressure/pressure_solver.hpp"
#include "runnel/sph/spatial_hash.hpp"
#include "runnel/sph/sph_settings.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// What one of the pressure solves has done so far in a run: solves, iterations, the solves that
// stopped at sph.dfsph_max_iterations with their error still above the tolerance, and the last
// solve's mean and worst error (fractions of ρ0).
struct SolveStats {
  std::uint64_t solves = 0, iterations = 0, capped = 0;
  double last_error = 0, worst_error = 0;
};
struct DfsphStats {
  SolveStats density, divergence;
};

// The incompressible solver, DFSPH (docs/sph.md): host code of cl/dfsph_density.cl and
// cl/dfsph_solve.cl, its passes over the particles of a built hash. Its step:
//   before the drift   the constant-density solve: the pressure impulse dt·a(κ) added to v keeps
//                      the density at ρ0 when the particles move at v + a·dt/2 + dt·a(κ);
//   after the drift    x(n+1) becomes the state (ρ is measured after the sort, by summation);
//   complete           ρ(n+1), the factors and the neighbour lists; a(n+1) (viscosity, gravity);
//                      v(n+1) = v(n+½) + a(n+1)·dt/2; the divergence-free solve on v(n+1).
class Dfsph final : public PressureSolver {
 public:
  Dfsph(ComputeContext& compute, cl::Program& program, const SphSettings& settings);

  void measure_rates(SphPipeline& p) override;
  void rehashed(SphPipeline& p) override;
  void before_drift(SphPipeline& p, double dt) override;
  void after_drift(SphPipeline& p, double dt) override;
  void complete(SphPipeline& p, double dt) override;
  bool closing_kick_in_stats() const override { return false; }
  // dt = cfl_flow · min(dx/|v|max, ½ sqrt(dx/|a|max)) with the non-pressure accelerations, and the
  // explicit viscosity's diffusion limit 0.125 h²/ν, ν = α c0 h / 10.
  double next_dt(const SphHealth& health) const override;
  double first_dt() const override { return settings_.dt_max; }
  bool density_floor_checked() const override { return false; }
  // Each particle's pressure (Pa) in the last step: ρ0 (κ + κ_v) of its two solves.
  std::vector<float> pressure(ParticleStore& store) const override;
  // The stats as JSON: solves, mean iterations, capped solves, last errors.
  JsonObject json() const override;
  // Its listed pairs (a neighbour's index and the pair's kernel gradient with its floor image's,
  // one float4 each, and with sph.dfsph_floor_images the image's normal gradient, one float) and
  // the terrain's tangent plane under each particle; the bytes those buffers hold now (0 before
  // the first density pass).
  std::size_t bytes_per_particle() const override;
  std::size_t allocated_bytes() const override;
  // The solves' kept pressures: their warm start.
  std::vector<ParticleField> kept_fields() const override { return {kKappa, kKappaV}; }

  const DfsphStats& stats() const { return stats_; }

 private:
  // ρ (summation), the solver's factor and θ at the hashed positions (into the store's spares:
  // valid until the next sort).
  void measure_density(ParticleStore& store, const SpatialHash& hash, DeviceTerrain& terrain);
  // Viscosity and gravity into a (kAx, kAy, kAz), after measure_density().
  void non_pressure_accelerations(ParticleStore& store, const SpatialHash& hash,
                                  DeviceTerrain& terrain);
  // v += a·dt/2: a step's closing half kick (the drift's kernel gives the opening one).
  void half_kick(ParticleStore& store, double dt);

  // Work-items a group of dfsph_density_change, which sums its errors in local memory
  // (cl/dfsph_solve.cl's DFSPH_GROUP).
  static constexpr std::size_t kGroup = 64;
  static constexpr std::size_t kSlots = 96;  // DFSPH_SLOTS of cl/dfsph_density.cl
  struct SolveResult {
    int iterations;
    bool capped;
    double mean_error, worst_error;
  };
  SolveResult solve(ParticleStore& store, const SpatialHash& hash, DeviceTerrain& terrain,
                    double dt, bool divergence);
  // Launches dfsph_density_change and reads the error sums: mean over the particles in the solve,
  // and the worst.
  std::pair<double, double> density_change(ParticleStore& store, bool iterate);
  void bind_neighbourhood(Kernel& k, ParticleStore& store, const SpatialHash& hash,
                          DeviceTerrain& terrain);
  // u = v + a·dt/2 into the three buffers u (the velocity itself, or a solve's spares).
  void launch_half_kick(ParticleStore& store, double dt, std::array<cl::Buffer*, 3> u);
  // Runs one solve and books it: its step (κ is kept × dt^k), its stats, a caution when capped.
  void solve_and_record(ParticleStore& store, const SpatialHash& hash, DeviceTerrain& terrain,
                        double dt, bool divergence);
  void caution(const char* solve, const SolveResult& r, double tolerance);

  ComputeContext& compute_;
  SphSettings settings_;
  Kernel density_, non_pressure_, half_kick_, pressure_acceleration_, density_change_, finish_;
  cl::Buffer errors_, error_max_;
  // Each particle's neighbours within the support and their pairs' ∇W_ij + ∇W_ij', kSlots float4s
  // a particle, the images' n·∇W_ij', kSlots floats a particle (cl/dfsph_density.cl), and the
  // terrain's tangent plane under each particle (n, d), from the density pass, for the solves.
  cl::Buffer pairs_, pair_images_, planes_;
  std::size_t list_capacity_ = 0;
  DfsphStats stats_;
  double density_dt_ = 0, divergence_dt_ = 0;  // the steps of the last solves (κ is kept × dt^k)
  bool cautioned_ = false;
};

}  // namespace runnel
