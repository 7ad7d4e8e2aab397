// SPDX-License-Identifier: MIT
#include "runnel/sph/pressure/wcsph/wcsph.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"
#include "runnel/sph/sph_solver.hpp"

namespace runnel {

Wcsph::Wcsph(ComputeContext& compute, cl::Program& program, const SphSettings& settings)
    : settings_(settings) {
  forces_ = Kernel(compute, program, "sph_forces");
  forces_direct_ = Kernel(compute, program, "sph_forces_direct");
  forces_inputs_ = Kernel(compute, program, "forces_inputs");
  continuity_ = Kernel(compute, program, "sph_continuity");
  continuity_direct_ = Kernel(compute, program, "sph_continuity_direct");
}

void Wcsph::bind_domain(Kernel& k, DeviceTerrain& terrain) {
  terrain.bind(k);
  terrain.bind_extent(k);
}

// ρ(n+1) = ρ(n) + dt·dρ/dt at x(n) with the actual displacements; the continuity pass's inputs
// come from the drift (bind_continuity_inputs).
void Wcsph::after_drift(SphPipeline& p, double dt) {
  for (Kernel* k : {&continuity_, &continuity_direct_}) {
    p.store.bind(*k, {kX, kY, kZ, kRho, kDrho});
    p.store.bind_new(*k, {kRho});
    bind_continuity_inputs(p.store, *k);
    bind_domain(*k, p.terrain);
    k->set("dt", static_cast<float>(dt));
  }
  p.hash.launch_tiled(continuity_, continuity_direct_);
  p.store.swap_scratch({kX, kY, kZ, kRho});  // x(n+1), ρ(n+1) become the state
}

void Wcsph::compute_forces(SphPipeline& p) {
  ParticleStore& store = p.store;
  const cl_uint n = static_cast<cl_uint>(store.size());
  const char* inputs[] = {"pressure", "p_over_rho2", "volume"};
  store.bind(forces_inputs_, {kRho});
  for (int s = 0; s < 3; ++s) forces_inputs_.set(inputs[s], store.spare(s));
  forces_inputs_.launch(round_up_work(n));

  for (Kernel* k : {&forces_, &forces_direct_}) {
    store.bind(*k, {kX, kY, kZ, kVx, kVy, kVz, kRho, kAx, kAy, kAz});
    for (int s = 0; s < 3; ++s) k->set(inputs[s], store.spare(s));
    bind_domain(*k, p.terrain);
  }
  p.hash.launch_tiled(forces_, forces_direct_);
}

double Wcsph::next_dt(const SphHealth& health) const {
  const SphSettings& s = settings_;
  double dt = s.h / (s.c0 + health.v_max);
  if (health.a_max > 0) dt = std::min(dt, std::sqrt(s.h / health.a_max));
  return dt * s.cfl;
}

// No fluid yet: the acoustic limit, so rain that arrives next starts stable.
double Wcsph::first_dt() const {
  return std::min(settings_.cfl * settings_.h / settings_.c0, settings_.dt_max);
}

std::vector<float> Wcsph::pressure(ParticleStore& store) const {
  std::vector<float> p = store.read_field(kRho);
  for (float& v : p) {
    const double r = v / settings_.rho0;
    const double tait = settings_.tait_b() * (std::pow(r, 7.0) - 1.0);
    v = static_cast<float>(settings_.clamp_negative_pressure ? std::max(0.0, tait) : tait);
  }
  return p;
}

}  // namespace runnel
