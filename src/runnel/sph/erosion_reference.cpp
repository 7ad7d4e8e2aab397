// SPDX-License-Identifier: MIT
#include "runnel/sph/erosion_reference.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/rng.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/terrain/terrain_normals.hpp"

namespace runnel::erosion_reference {
namespace {

constexpr std::uint64_t kErosionStream = 0x65726f64ULL;  // "erod", as cl/erode.cl

double draw(std::uint64_t seed, std::uint32_t id, std::uint64_t step, std::uint32_t which) {
  return rng_uniform(seed, kErosionStream + which, (step << 32) | id);
}

// cl/footprint.cl's spread_quanta: sign·quanta over the vertices within radius R of (x, z), by
// systematic sampling of the separable weights (1 − (d/R)²)².
void spread(std::vector<std::int64_t>& delta, const Heightmap& t, double R, double x, double z,
            std::int64_t quanta, int sign, double u) {
  if (quanta == 0) return;
  auto weight = [&](double d) {
    const double s = std::max(0.0, 1 - d * d / (R * R));
    return s * s;
  };
  const int i0 = std::max(0, static_cast<int>(std::ceil((x - R) / t.cell)));
  const int i1 = std::min(t.nx - 1, static_cast<int>(std::floor((x + R) / t.cell)));
  const int j0 = std::max(0, static_cast<int>(std::ceil((z - R) / t.cell)));
  const int j1 = std::min(t.ny - 1, static_cast<int>(std::floor((z + R) / t.cell)));
  double sum_x = 0, sum_z = 0;
  for (int i = i0; i <= i1; ++i) sum_x += weight(i * t.cell - x);
  for (int j = j0; j <= j1; ++j) sum_z += weight(j * t.cell - z);
  if (!(sum_x > 0 && sum_z > 0)) {
    const int i = std::clamp(static_cast<int>(std::lround(x / t.cell)), 0, t.nx - 1);
    const int j = std::clamp(static_cast<int>(std::lround(z / t.cell)), 0, t.ny - 1);
    delta[static_cast<std::size_t>(j) * t.nx + i] += sign * quanta;
    return;
  }
  const double scale = static_cast<double>(quanta) / (sum_x * sum_z);
  double cumulative = 0;
  std::int64_t given = 0;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      cumulative += weight(j * t.cell - z) * weight(i * t.cell - x);
      const std::int64_t upto =
          (i == i1 && j == j1)
              ? quanta
              : std::min(quanta, static_cast<std::int64_t>(std::floor(cumulative * scale + u)));
      if (upto > given) {
        delta[static_cast<std::size_t>(j) * t.nx + i] += sign * (upto - given);
        given = upto;
      }
    }
  }
}

}  // namespace

Exchange exchange(const HostParticles& p, const std::vector<float>& depth, const Heightmap& t,
                  const SphSettings& sph, const ErosionSettings& e, double Q, double dt,
                  std::uint64_t seed, std::uint64_t step) {
  Exchange out;
  out.sediment = p.sediment;
  out.id = p.id;
  out.delta.assign(t.size(), 0);
  const std::vector<float> normals = terrain_normals_reference(t);
  const double volume = sph.spacing * sph.spacing * sph.spacing;
  const double R = e.footprint_radius, mf = e.morphological_factor;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] & kDeadFlag) continue;
    const double x = p.f[kX][i], z = p.f[kZ][i];
    const std::int64_t carried = p.sediment[i];
    const std::uint32_t id = p.id[i];
    if (p.f[kAge][i] > p.f[kLifespan][i]) {  // evaporation
      const std::int64_t kept = std::min(
          carried,
          static_cast<std::int64_t>(std::floor(static_cast<double>(carried) * e.deposit_fraction)));
      spread(out.delta, t, R, x, z, kept, 1, draw(seed, id, step, 1));
      out.lost += carried - kept;
      ++out.evaporated;
      out.sediment[i] = 0;
      out.id[i] |= kDeadFlag;
      continue;
    }
    const SurfacePointReference s = surface_point(t, normals, x, z);
    const double* n = s.normal;
    const double gap = (p.f[kY][i] - s.height) * n[1] - sph.contact_radius;
    const double D = std::max<double>(depth[i], 1e-6);
    if (!(p.contacts[i] & kTouchingFlag) && gap > D) continue;  // in the air, not touching
    const double u0 = draw(seed, id, step, 0), u1 = draw(seed, id, step, 1);
    auto quanta = [&](double amount) {
      return static_cast<std::int64_t>(std::floor(amount / Q + u0));
    };
    if (e.model == "acidity") {
      if ((p.contacts[i] & ~kTouchingFlag) < static_cast<std::uint64_t>(e.capacity_contacts)) {
        const std::int64_t q = quanta(e.acidity * t.cell * t.cell);
        if (q > 0) {
          spread(out.delta, t, R, x, z, q, -1, u1);
          out.sediment[i] = static_cast<std::int32_t>(carried + q);
        }
      }
      continue;
    }
    const double v[3] = {p.f[kVx][i], p.f[kVy][i], p.f[kVz][i]};
    const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    const double along[3] = {v[0] - vn * n[0], v[1] - vn * n[1], v[2] - vn * n[2]};
    const double speed = std::sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]);
    if (e.model == "bedload") {
      const SedimentSettings& g = e.sediment;
      const double q = bedload_rate(g, sph.manning_n, sph.gravity, D, speed);
      const double capacity =
          speed > 0 ? std::min(mf * q / (speed * D * (1 - g.porosity)), mf * e.max_concentration)
                    : 0.0;
      const double load = static_cast<double>(carried) * Q;
      const double relaxed = -std::expm1(-dt * std::max(speed, e.settling) / g.adaptation_length);
      const double difference = capacity * volume - load;
      if (difference > 0) {
        const std::int64_t q_taken = quanta(difference * relaxed);
        if (q_taken > 0) {
          spread(out.delta, t, R, x, z, q_taken, -1, u1);
          out.sediment[i] = static_cast<std::int32_t>(carried + q_taken);
        }
      } else {
        const std::int64_t dropped = std::min(carried, quanta(-difference * relaxed));
        if (dropped > 0) {
          spread(out.delta, t, R, x, z, dropped, 1, u1);
          out.sediment[i] = static_cast<std::int32_t>(carried - dropped);
        }
      }
      continue;
    }
    const double tau =
        sph.rho0 * sph.gravity * sph.manning_n * sph.manning_n * speed * speed / std::cbrt(D);
    const double excess = std::max(tau * speed - e.critical_power, 0.0);
    const double sin_slope = speed > 0 ? std::max(0.0, -along[1] / speed) : 0.0;  // along the flow
    const double capacity =
        mf * std::min(e.transport * sph.rho0 * sph.gravity / e.bed_density * sin_slope,
                      e.max_concentration);
    const double area = volume / D;
    const double load = static_cast<double>(carried) * Q, c = load / volume;
    if (c < capacity) {
      const double rate = mf * e.erodibility / e.bed_density * excess * (1 - c / capacity);
      const std::int64_t q = quanta(std::min(rate * area * dt, (capacity - c) * volume));
      if (q > 0) {
        spread(out.delta, t, R, x, z, q, -1, u1);
        out.sediment[i] = static_cast<std::int32_t>(carried + q);
      }
    } else {
      const double rate = e.settling * (c - capacity);
      const std::int64_t q =
          std::min(carried, quanta(std::min(rate * area * dt, load - capacity * volume)));
      if (q > 0) {
        spread(out.delta, t, R, x, z, q, 1, u1);
        out.sediment[i] = static_cast<std::int32_t>(carried - q);
      }
    }
  }
  return out;
}

}  // namespace runnel::erosion_reference
