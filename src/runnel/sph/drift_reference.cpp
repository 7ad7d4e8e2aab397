// SPDX-License-Identifier: MIT
#include "runnel/sph/drift_reference.hpp"

#include <cmath>

namespace runnel::drift_reference {
namespace {

Vec operator+(Vec a, const Vec& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Vec operator-(Vec a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec operator*(double k, const Vec& a) {
  return {k * a[0], k * a[1], k * a[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

struct Surface {
  Vec normal;
  double lift;  // the contact surface's height above the terrain
  double height(const Plane& p, double x, double z) const {
    return p.y0 + p.slope_x * x + p.slope_z * z + lift;
  }
};

Vec contact_response(const Vec& v, const Vec& n, double e) {
  const double vn = dot(v, n);
  return vn >= 0 ? v : v - ((1.0 + e) * vn) * n;
}

// cl/integrate.cl's rebound(): the impact at fraction t, the rebound, held on the surface if the
// rebound cannot lift it clear before the step ends.
Vec rebound(Vec& v, const Vec& a, const Vec& n, double t, double dt, double e) {
  const Vec impact = v + (dt * (t - 0.5)) * a;
  Vec out = contact_response(impact, n, e);
  const double remaining = (1.0 - t) * dt;
  Vec a_rest = a;
  const double an = dot(a, n), vn = dot(out, n);
  if (an < 0 && vn + an * remaining < 0) {
    a_rest = a - an * n;
    out = out - vn * n;
  }
  v = out + (dt * (0.5 - t)) * a_rest;
  return remaining * out + (0.5 * remaining * remaining) * a_rest;
}

}  // namespace

Drifted drift(const Particle& p, const Plane& plane, const SphSettings& s, double dt) {
  Surface surface;
  const double len = std::sqrt(plane.slope_x * plane.slope_x + 1 + plane.slope_z * plane.slope_z);
  surface.normal = {-plane.slope_x / len, 1 / len, -plane.slope_z / len};
  surface.lift = s.contact_radius / std::max(surface.normal[1], 0.2);
  Drifted out;
  Vec v = p.v + (0.5 * dt) * p.a;  // the opening half kick
  Vec x = p.x + dt * v;
  if (x[0] < 0 || x[0] > plane.lx || x[2] < 0 || x[2] > plane.lz) {
    out.x = x, out.v = v, out.outflow = true;
    return out;
  }
  const Vec& n = surface.normal;
  const Vec& start = p.x;
  bool touching = false;
  const double gap0 = start[1] - surface.height(plane, start[0], start[2]);
  if (gap0 <= s.surface_eps && (dot(v, n) < 0 || x[1] < surface.height(plane, x[0], x[2]))) {
    touching = true;
    x = start + rebound(v, p.a, n, 0.0, dt, s.restitution);
  } else {
    // The first crossing of the plane along the segment: the vertical gap falls linearly.
    const double gap1 = x[1] - surface.height(plane, x[0], x[2]);
    if (gap0 >= 0 && gap1 < 0) {
      const double t = gap0 / (gap0 - gap1);
      const Vec hit = start + t * (x - start);
      touching = true;
      x = hit + rebound(v, p.a, n, t, dt, s.restitution);
      // A second crossing of the same plane after a rebound is what the kernel's "again" catches.
      const Vec from = hit + s.surface_eps * n;
      const double g0 = from[1] - surface.height(plane, from[0], from[2]);
      const double g1 = x[1] - surface.height(plane, x[0], x[2]);
      if (g0 >= 0 && g1 < 0) {
        v = contact_response(v, n, s.restitution);
        x = from + (g0 / (g0 - g1)) * (x - from);
      }
    }
  }
  const double below = surface.height(plane, x[0], x[2]) - x[1];
  if (below > 0) {
    x[1] += below;
    v = contact_response(v, n, s.restitution);
    touching = true;
  }
  touching = touching || -below <= s.surface_eps;
  const double depth = std::max(p.depth, 1e-6);
  if (touching || (-below) * n[1] <= depth) {  // Manning's bed friction, implicit
    const double vn = dot(v, n);
    const Vec vt = v - vn * n;
    const double k = s.gravity * s.manning_n * s.manning_n / (depth * std::cbrt(depth));
    v = vn * n + (1.0 / (1.0 + dt * k * std::sqrt(dot(vt, vt)))) * vt;
  }
  out.x = x, out.v = v, out.touching = touching;
  return out;
}

}  // namespace runnel::drift_reference
