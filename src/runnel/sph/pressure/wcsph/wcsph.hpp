// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/sph/pressure/pressure_solver.hpp"
#include "runnel/sph/sph_settings.hpp"

namespace runnel {

// The weakly compressible solver (physics.md §2, docs/sph.md): the density integrated by the
// continuity equation, the pressure from it by the Tait equation, kick-drift-kick leapfrog with a
// time step set by the sound speed. Host code of cl/sph_continuity.cl and cl/sph_forces.cl. Its
// step:
//   after the drift   ρ(n+1) = ρ(n) + dt·dρ/dt with the drift's actual displacements; x(n+1),
//                     ρ(n+1) become the state;
//   complete          a(n+1) at x(n+1), ρ(n+1); the step's statistics pass gives the closing kick.
class Wcsph final : public PressureSolver {
 public:
  Wcsph(ComputeContext& compute, cl::Program& program, const SphSettings& settings);

  void measure_rates(SphPipeline& p) override { compute_forces(p); }
  void after_drift(SphPipeline& p, double dt) override;
  void complete(SphPipeline& p, double) override { compute_forces(p); }
  bool closing_kick_in_stats() const override { return true; }
  // The acoustic CFL and the acceleration limit, dt = cfl · min(h/(c0 + |v|max), sqrt(h/|a|max)).
  double next_dt(const SphHealth& health) const override;
  double first_dt() const override;
  bool density_floor_checked() const override { return true; }
  // The Tait equation of each particle's density.
  std::vector<float> pressure(ParticleStore& store) const override;
  JsonObject json() const override { return JsonObject().add("solver", "wcsph"); }

 private:
  void compute_forces(SphPipeline& p);
  // The terrain boundary and the domain's extent (walls): what both neighbour passes see.
  static void bind_domain(Kernel& k, DeviceTerrain& terrain);

  SphSettings settings_;
  // The neighbour passes come in pairs: tiled, and direct for the lone tiles (SpatialHash).
  Kernel forces_inputs_, forces_, forces_direct_, continuity_, continuity_direct_;
};

}  // namespace runnel
