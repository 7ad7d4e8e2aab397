// SPDX-License-Identifier: MIT
#include "runnel/sph/sph_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace runnel::sph_reference {

namespace {

using Vec = std::array<double, 3>;

double alpha(double h) {
  return 21.0 / (16.0 * M_PI * h * h * h);
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec position(const HostParticles& p, std::size_t i) {
  return {p.f[kX][i], p.f[kY][i], p.f[kZ][i]};
}
Vec velocity(const HostParticles& p, std::size_t i) {
  return {p.f[kVx][i], p.f[kVy][i], p.f[kVz][i]};
}

double pressure(double rho, const SphSettings& s) {
  const double p = s.tait_b() * (std::pow(rho / s.rho0, 7) - 1.0);
  return s.clamp_negative_pressure ? std::max(p, 0.0) : p;
}

// j itself (wx = wz = 0) and its mirror images across the tank walls within 2h of x_i: the
// position and the velocity sign of each image.
struct Image {
  Vec x;
  double sx, sz;  // velocity signs
  bool ghost;
};
std::vector<Image> images(const Vec& xi, const Vec& xj, const SphSettings& s, const Boundary& b) {
  std::vector<Image> out{{xj, 1, 1, false}};
  if (!s.walls) return out;
  const double reach = 2 * s.h;
  const bool near_x[3] = {true, xi[0] < reach, b.lx - xi[0] < reach};
  const bool near_z[3] = {true, xi[2] < reach, b.lz - xi[2] < reach};
  const double gx[3] = {xj[0], -xj[0], 2 * b.lx - xj[0]};
  const double gz[3] = {xj[2], -xj[2], 2 * b.lz - xj[2]};
  for (int wx = 0; wx < 3; ++wx) {
    for (int wz = 0; wz < 3; ++wz) {
      if ((wx == 0 && wz == 0) || !near_x[wx] || !near_z[wz]) continue;
      out.push_back({{gx[wx], xj[1], gz[wz]}, wx ? -1.0 : 1.0, wz ? -1.0 : 1.0, true});
    }
  }
  return out;
}

double fullness(double shepard, double d, double rhoi, const SphSettings& s) {
  const double full = 1.0 - wall_volume(d, s.h) - s.mass() / rhoi * wendland_w(0, s.h);
  const double x = std::clamp((shepard / full - 0.8) / 0.15, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

}  // namespace

double wendland_w(double r, double h) {
  const double q = r / h;
  if (q >= 2.0) return 0.0;
  return alpha(h) * std::pow(1.0 - 0.5 * q, 4) * (2.0 * q + 1.0);
}

double wendland_grad_factor(double r, double h) {
  const double q = r / h;
  if (q >= 2.0) return 0.0;
  return -5.0 * alpha(h) / (h * h) * std::pow(1.0 - 0.5 * q, 3);
}

double wall_integral(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  const double a = q * q / 2 - 5 * std::pow(q, 4) / 8 + std::pow(q, 5) / 2 -
                   5 * std::pow(q, 6) / 32 + std::pow(q, 7) / 56;
  return 2.0 * M_PI * alpha(h) * h * h * (2.0 / 7.0 - a);
}

double wall_moment_normal(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  return 0.5 - 7 * std::pow(q, 3) / 8 + 21 * std::pow(q, 5) / 16 - 35 * std::pow(q, 6) / 32 +
         45 * std::pow(q, 7) / 128 - 21 * std::pow(q, 8) / 512;
}

double wall_moment_tangent(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  return 0.5 - 3 * q / 4 + 7 * std::pow(q, 3) / 16 - 21 * std::pow(q, 5) / 64 +
         7 * std::pow(q, 6) / 32 - 15 * std::pow(q, 7) / 256 + 3 * std::pow(q, 8) / 512;
}

double wall_volume(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  auto big_b = [](double u) {
    return std::pow(u, 3) / 6 - std::pow(u, 5) / 8 + std::pow(u, 6) / 12 -
           5 * std::pow(u, 7) / 224 + std::pow(u, 8) / 448;
  };
  return 2.625 * (2.0 / 7.0 * (2.0 - q) - big_b(2.0) + big_b(q));
}

std::vector<double> continuity_rates(const HostParticles& before, const HostParticles& after,
                                     double dt, const SphSettings& s, const Boundary& b) {
  const std::size_t n = before.size();
  const double h = s.h, m = s.mass(), eta2 = 0.01 * h * h;
  const double hydrostatic = s.rho0 * s.gravity / (s.c0 * s.c0);
  std::vector<Vec> mid(n), vel(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec x0 = position(before, i), x1 = position(after, i);
    for (int a = 0; a < 3; ++a) {
      mid[i][a] = 0.5 * (x0[a] + x1[a]);
      vel[i][a] = (x1[a] - x0[a]) / dt;
    }
  }
  std::vector<double> drho(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double rhoi = before.f[kRho][i];
    double fluid = 0, ghosts = 0, shepard = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const double rhoj = before.f[kRho][j];
      if (dot(sub(mid[i], mid[j]), sub(mid[i], mid[j])) >= 4 * h * h) continue;
      for (const Image& g : images(mid[i], mid[j], s, b)) {
        if (!g.ghost && i == j) continue;
        const Vec x = sub(mid[i], g.x);
        const double r2 = dot(x, x);
        if (r2 >= 4 * h * h) continue;
        const double r = std::sqrt(r2), f = wendland_grad_factor(r, h);
        const Vec vj = {g.sx * vel[j][0], vel[j][1], g.sz * vel[j][2]};
        const double vdotx = dot(sub(vel[i], vj), x);
        shepard += m / rhoj * wendland_w(r, h);
        if (g.ghost) {
          ghosts += m * vdotx * f;
        } else {
          const double rho_dynamic = (rhoi - rhoj) + hydrostatic * x[1];
          fluid += m * vdotx * f +
                   2 * s.delta * h * s.c0 * (m / rhoj) * rho_dynamic * r2 * f / (r2 + eta2);
        }
      }
    }
    const double d = mid[i][1] - b.floor_height;
    const double theta = fullness(shepard, d, rhoi, s);
    drho[i] = fluid + theta * (ghosts - 2 * rhoi * vel[i][1] * wall_integral(d, h));
  }
  return drho;
}

Accelerations accelerations(const HostParticles& p, const SphSettings& s, const Boundary& b) {
  const std::size_t n = p.size();
  const double h = s.h, m = s.mass(), eta2 = 0.01 * h * h;
  Accelerations r{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec xi = position(p, i), vi = velocity(p, i);
    const double rhoi = p.f[kRho][i], pi = pressure(rhoi, s);
    Vec acc{0, 0, 0}, ghosts{0, 0, 0}, gp{0, 0, 0};
    double shepard = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const Vec xj = position(p, j), vj0 = velocity(p, j);
      if (dot(sub(xi, xj), sub(xi, xj)) >= 4 * h * h) continue;
      const double rhoj = p.f[kRho][j], pj = pressure(rhoj, s);
      for (const Image& g : images(xi, xj, s, b)) {
        if (!g.ghost && i == j) continue;
        const Vec x = sub(xi, g.x);
        const double r2 = dot(x, x);
        if (r2 >= 4 * h * h) continue;
        const double rr = std::sqrt(r2), f = wendland_grad_factor(rr, h);
        const Vec vj = {g.sx * vj0[0], vj0[1], g.sz * vj0[2]};
        const double vdotx = dot(sub(vi, vj), x);
        const double visc =
            vdotx < 0 ? -s.alpha_visc * s.c0 * (h * vdotx / (r2 + eta2)) / (0.5 * (rhoi + rhoj))
                      : 0.0;
        const double k = -m * (pi / (rhoi * rhoi) + pj / (rhoj * rhoj) + visc) * f;
        Vec& target = g.ghost ? ghosts : acc;
        for (int a = 0; a < 3; ++a) {
          target[a] += k * x[a];
          gp[a] += m / rhoj * (pj - pi) * f * x[a];
        }
        shepard += m / rhoj * wendland_w(rr, h);
      }
    }
    // The flat floor: normal +y. Mirror pressure and the extrapolated gradient's support.
    const double d = xi[1] - b.floor_height;
    const double theta = fullness(shepard, d, rhoi, s);
    Vec wall{0, 0, 0};
    if (wall_integral(d, h) > 0) {
      const double am = wall_moment_normal(d, h), bm = wall_moment_tangent(d, h);
      wall[0] = -bm / (1 - bm) * gp[0] / rhoi;
      wall[1] = 2 * pi / rhoi * wall_integral(d, h) - am / (1 - am) * gp[1] / rhoi;
      wall[2] = -bm / (1 - bm) * gp[2] / rhoi;
    }
    r.ax[i] = acc[0] + theta * (ghosts[0] + wall[0]);
    r.ay[i] = acc[1] + theta * (ghosts[1] + wall[1]) - s.gravity;
    r.az[i] = acc[2] + theta * (ghosts[2] + wall[2]);
  }
  return r;
}

}  // namespace runnel::sph_reference
