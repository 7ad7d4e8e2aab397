// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_settings.hpp"

// A plain C++ double-precision reference of the SPH equations (physics.md §2; docs/sph.md): the
// oracle the OpenCL kernels in cl/sph_kernel.cl, cl/sph_boundary.cl, cl/sph_continuity.cl and
// cl/sph_forces.cl are tested against. Brute force, O(N²).
namespace runnel::sph_reference {

double wendland_w(double r, double h);
double wendland_grad_factor(double r, double h);  // ∇_i W_ij = F · x_ij
double wall_integral(double d, double h);         // G(d) = 2π ∫_d^{2h} W(r) r dr
double wall_moment_normal(double d, double h);    // a(d/h)
double wall_moment_tangent(double d, double h);   // b(d/h)
double wall_volume(double d, double h);           // Γ(d) = ∫_d^{2h} G(s) ds

// The fluid around the particles: a flat floor y = floor_height (the terrain's tangent plane when
// the terrain is flat), and with settings.walls the tank's vertical walls at x = 0, x = lx, z = 0,
// z = lz.
struct Boundary {
  double floor_height = -1e30;  // far below: no floor
  double lx = 0, lz = 0;
};

// dρ/dt of the continuity pass for a drift from `before` to `after` (the same particles, in the
// same order) lasting dt, with the densities of `before` (cl/sph_continuity.cl).
std::vector<double> continuity_rates(const HostParticles& before, const HostParticles& after,
                                     double dt, const SphSettings& settings,
                                     const Boundary& boundary);

struct Accelerations {
  std::vector<double> ax, ay, az;
};
// The accelerations of the force pass, gravity included (cl/sph_forces.cl).
Accelerations accelerations(const HostParticles& particles, const SphSettings& settings,
                            const Boundary& boundary);

}  // namespace runnel::sph_reference
