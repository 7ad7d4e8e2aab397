// SPDX-License-Identifier: MIT
// The oracle of cl/models/pipe_godunov.cl in plain C++ and double precision: the bed's and depth's
// limited slopes, the HLL fluxes on Audusse's reconstruction, the update with the bed's centred
// source and Manning friction.
#include <algorithm>
#include <array>
#include <cmath>

#include "runnel/models/pipe_reference.hpp"

namespace runnel::pipe_reference {
namespace {

constexpr double kDry = 1e-6;  // m: thinner water has no velocity (GODUNOV_DRY)

using Flux = std::array<double, 3>;  // mass, normal momentum, tangential momentum

Flux hll(double hl, double unl, double utl, double hr, double unr, double utr, double g) {
  if (hl <= kDry && hr <= kDry) return {0, 0, 0};
  const double cl = std::sqrt(g * hl), cr = std::sqrt(g * hr);
  double sl = std::min(unl - cl, unr - cr), sr = std::max(unl + cl, unr + cr);
  if (hl <= kDry) sl = unr - 2 * cr, sr = unr + cr;
  if (hr <= kDry) sl = unl - cl, sr = unl + 2 * cl;
  const Flux fl = {hl * unl, hl * unl * unl + 0.5 * g * hl * hl, hl * unl * utl};
  const Flux fr = {hr * unr, hr * unr * unr + 0.5 * g * hr * hr, hr * unr * utr};
  if (sl >= 0) return fl;
  if (sr <= 0) return fr;
  const Flux ul = {hl, hl * unl, hl * utl}, ur = {hr, hr * unr, hr * utr};
  Flux f;
  for (int c = 0; c < 3; ++c)
    f[c] = (sr * fl[c] - sl * fr[c] + sl * sr * (ur[c] - ul[c])) / (sr - sl);
  return f;
}

double minmod(double before, double after) {
  if (!(before * after > 0)) return 0;
  return std::fabs(before) < std::fabs(after) ? before : after;
}

// A face as the cells on either side see it: the mass flux, the normal momentum flux with each
// side's pressure correction, the tangential momentum flux.
struct Face {
  double mass = 0, momentum_a = 0, momentum_b = 0, tangential = 0;
};

Face face_of(const Flux& f) {
  return {f[0], f[1], f[1], f[2]};
}

// The map's edge after a cell (its right or lower face) and before one (its left or upper face),
// for its depth and normal and tangential velocities: a mirror (closed) or dry, lower ground.
Face edge_after(double h, double un, double ut, bool closed, double g) {
  return face_of(closed ? hll(h, un, ut, h, -un, ut, g) : hll(h, un, ut, 0, 0, 0, g));
}
Face edge_before(double h, double un, double ut, bool closed, double g) {
  return face_of(closed ? hll(h, -un, ut, h, un, ut, g) : hll(0, 0, 0, h, un, ut, g));
}

Face reconstructed(double za, double ha, double una, double uta, double zb, double hb, double unb,
                   double utb, double g) {
  const double z = std::max(za, zb);
  const double sa = std::max(0.0, ha + za - z), sb = std::max(0.0, hb + zb - z);
  const Flux f = hll(sa, una, uta, sb, unb, utb, g);
  return {f[0], f[1] + 0.5 * g * (ha * ha - sa * sa), f[1] + 0.5 * g * (hb * hb - sb * sb), f[2]};
}

}  // namespace

void godunov_water(State& st, int nx, int ny, double l, double q, const PipeSettings& s,
                   double dt) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  const double g = s.gravity;
  std::vector<double> z(n), h(n);
  for (std::size_t k = 0; k < n; ++k) {
    z[k] = static_cast<double>(st.height[k]) * q;
    h[k] = st.depth[k] + dt * s.rain;
  }
  // Per cell and direction (x, z): the bed's and the depth's limited slopes over one cell.
  std::vector<std::array<double, 4>> slope(n, {0, 0, 0, 0});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      for (int d = 0; d < 2; ++d) {
        const bool inner = d == 0 ? (i > 0 && i < nx - 1) : (j > 0 && j < ny - 1);
        if (!inner) continue;
        const std::size_t a = d == 0 ? k - 1 : k - nx, b = d == 0 ? k + 1 : k + nx;
        if (!(std::min({h[a], h[k], h[b]}) > kDry)) continue;
        const double bed = minmod(z[k] - z[a], z[b] - z[k]), dh = minmod(h[k] - h[a], h[b] - h[k]);
        slope[k][2 * d] = bed;
        slope[k][2 * d + 1] = std::copysign(std::min(std::fabs(dh), std::fabs(bed)), dh);
      }
    }
  auto velocity = [&](std::size_t k, int c) { return st.velocity[2 * k + c]; };
  // The face between cells k and m along direction d (0: x, 1: z), each side's bed and depth moved
  // half a cell along their slopes; the normal velocity is component d.
  auto between = [&](std::size_t k, std::size_t m, int d) {
    return reconstructed(z[k] + 0.5 * slope[k][2 * d], h[k] + 0.5 * slope[k][2 * d + 1],
                         velocity(k, d), velocity(k, 1 - d), z[m] - 0.5 * slope[m][2 * d],
                         h[m] - 0.5 * slope[m][2 * d + 1], velocity(m, d), velocity(m, 1 - d), g);
  };
  // Each cell's right (x) and lower (z) faces.
  std::vector<Face> right(n), lower(n);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double u = velocity(k, 0), v = velocity(k, 1);
      right[k] = i < nx - 1 ? between(k, k + 1, 0) : edge_after(h[k], u, v, s.closed(), g);
      lower[k] = j < ny - 1 ? between(k, k + nx, 1) : edge_after(h[k], v, u, s.closed(), g);
    }
  const double sdt = dt / l;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double u = velocity(k, 0), v = velocity(k, 1);
      const Face left = i > 0 ? right[k - 1] : edge_before(h[k], u, v, s.closed(), g);
      const Face upper = j > 0 ? lower[k - nx] : edge_before(h[k], v, u, s.closed(), g);
      const Face& r = right[k];
      const Face& b = lower[k];
      const double h_new = std::max(0.0, h[k] - sdt * (r.mass - left.mass + b.mass - upper.mass));
      const double qx = h[k] * u - sdt * (r.momentum_a - left.momentum_b + b.tangential -
                                          upper.tangential + g * h[k] * slope[k][0]);
      const double qz = h[k] * v - sdt * (b.momentum_a - upper.momentum_b + r.tangential -
                                          left.tangential + g * h[k] * slope[k][2]);
      double un = 0, vn = 0;
      if (h_new > kDry) {
        un = qx / h_new, vn = qz / h_new;
        if (s.manning_n > 0) {
          const double d = std::max(h_new, 1e-3);
          const double damp =
              1 + dt * g * s.manning_n * s.manning_n * std::hypot(un, vn) / std::pow(d, 4.0 / 3.0);
          un /= damp, vn /= damp;
        }
      }
      st.depth[k] = h_new * std::exp(-s.evaporation * dt);
      st.velocity[2 * k] = un, st.velocity[2 * k + 1] = vn;
      st.flux[4 * k + 0] = std::max(-left.mass, 0.0) * l;
      st.flux[4 * k + 1] = std::max(r.mass, 0.0) * l;
      st.flux[4 * k + 2] = std::max(-upper.mass, 0.0) * l;
      st.flux[4 * k + 3] = std::max(b.mass, 0.0) * l;
    }
}

}  // namespace runnel::pipe_reference
