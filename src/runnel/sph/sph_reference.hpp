// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_settings.hpp"

// A plain C++ double-precision reference of the SPH equations (physics.md §2): the oracle the
// OpenCL kernels in cl/sph_kernel.cl and cl/sph_forces.cl are tested against. Brute force, O(N²).
namespace runnel::sph_reference {

double wendland_w(double r, double h);
double wendland_grad_factor(double r, double h);  // ∇_i W_ij = F · x_ij
double wall_integral(double d, double h);         // G(d) = 2π ∫_d^{2h} W(r) r dr
double wall_moment_normal(double d, double h);    // a(d/h)
double wall_moment_tangent(double d, double h);   // b(d/h)

struct Rates {
  std::vector<double> ax, ay, az, drho;
};
// Particle–particle rates plus gravity; no boundary terms (for particles far from every wall).
Rates interaction_rates(const HostParticles& particles, const SphSettings& settings);

}  // namespace runnel::sph_reference
