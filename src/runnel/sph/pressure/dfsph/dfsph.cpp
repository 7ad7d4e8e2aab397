// SPDX-License-Identifier: MIT
#include "runnel/sph/pressure/dfsph/dfsph.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <tuple>

#include "runnel/compute/launch.hpp"

namespace runnel {
namespace {

// The store's spares during the solves (valid from measure_density() to the next sort).
enum DfsphSpare : int { kFactor = 0, kTheta = 1, kSource = 2, kPressureAx = 3, kListed = 6 };
constexpr double kErrorQuantum = 1e-9;  // DFSPH_ERROR_QUANTUM of cl/dfsph_solve.cl

}  // namespace

Dfsph::Dfsph(ComputeContext& compute, cl::Program& program, const SphSettings& settings)
    : compute_(compute), settings_(settings) {
  density_ = Kernel(compute, program, "dfsph_density");
  non_pressure_ = Kernel(compute, program, "dfsph_non_pressure");
  half_kick_ = Kernel(compute, program, "dfsph_half_kick");
  pressure_acceleration_ = Kernel(compute, program, "dfsph_pressure_acceleration");
  density_change_ = Kernel(compute, program, "dfsph_density_change");
  finish_ = Kernel(compute, program, "dfsph_finish");
  errors_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, 2 * sizeof(cl_long));
  error_max_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, sizeof(cl_uint));
}

void Dfsph::bind_neighbourhood(Kernel& k, ParticleStore& store, const SpatialHash& hash,
                               DeviceTerrain& terrain) {
  store.bind(k, {kX, kY, kZ});
  hash.bind_cells(k);
  if (k.has("terrain_height")) terrain.bind(k);
  terrain.bind_extent(k);
}

void Dfsph::measure_density(ParticleStore& store, const SpatialHash& hash, DeviceTerrain& terrain) {
  const std::size_t n = store.size();
  if (n == 0) return;
  if (n > list_capacity_) {  // the lists grow with the particles, by the store's factor
    list_capacity_ = std::max(n, list_capacity_ + list_capacity_ / 2);
    pairs_ = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE,
                        list_capacity_ * kSlots * sizeof(cl_float4));
    // The images' terms only where the terrain is mirrored (a placeholder float otherwise).
    pair_images_ =
        cl::Buffer(compute_.context(), CL_MEM_READ_WRITE,
                   settings_.dfsph_floor_images ? list_capacity_ * kSlots * sizeof(cl_float)
                                                : sizeof(cl_float));
    planes_ =
        cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, 4 * list_capacity_ * sizeof(cl_float));
  }
  bind_neighbourhood(density_, store, hash, terrain);
  store.bind(density_, {kRho});
  density_.set("factor", store.spare(kFactor)).set("theta", store.spare(kTheta));
  density_.set("pairs", pairs_).set("pair_image", pair_images_);
  density_.set("neighbour_count", store.spare(kListed)).set("planes", planes_);
  density_.launch(round_up_work(n));
}

void Dfsph::non_pressure_accelerations(ParticleStore& store, const SpatialHash& hash,
                                       DeviceTerrain& terrain) {
  const std::size_t n = store.size();
  if (n == 0) return;
  bind_neighbourhood(non_pressure_, store, hash, terrain);
  store.bind(non_pressure_, {kVx, kVy, kVz, kAx, kAy, kAz});
  non_pressure_.set("pairs", pairs_).set("neighbour_count", store.spare(kListed));
  non_pressure_.set("planes", planes_).set("theta", store.spare(kTheta));
  non_pressure_.launch(round_up_work(n));
}

void Dfsph::half_kick(ParticleStore& store, double dt) {
  const std::size_t n = store.size();
  if (n == 0) return;
  launch_half_kick(store, dt, {&store.buffer(kVx), &store.buffer(kVy), &store.buffer(kVz)});
}

void Dfsph::launch_half_kick(ParticleStore& store, double dt, std::array<cl::Buffer*, 3> u) {
  store.bind(half_kick_, {kVx, kVy, kVz, kAx, kAy, kAz});
  half_kick_.set("ux", *u[0]).set("uy", *u[1]).set("uz", *u[2]);
  half_kick_.set("half_dt", static_cast<float>(0.5 * dt)).launch(round_up_work(store.size()));
}

void Dfsph::measure_rates(SphPipeline& p) {
  measure_density(p.store, p.hash, p.terrain);
  non_pressure_accelerations(p.store, p.hash, p.terrain);
}

void Dfsph::rehashed(SphPipeline& p) {
  measure_density(p.store, p.hash, p.terrain);  // the factors and the neighbour lists
}

// The non-pressure forces are leapfrogged around the pressure impulse, so a drop's flight and
// bounce are the weakly compressible solver's.
void Dfsph::before_drift(SphPipeline& p, double dt) {
  solve_and_record(p.store, p.hash, p.terrain, dt, /*divergence=*/false);
}

void Dfsph::after_drift(SphPipeline& p, double) {
  p.store.swap_scratch({kX, kY, kZ});  // x(n+1); ρ(n+1) is measured after the sort
}

void Dfsph::complete(SphPipeline& p, double dt) {
  measure_density(p.store, p.hash, p.terrain);             // ρ(n+1), the solver's factors
  non_pressure_accelerations(p.store, p.hash, p.terrain);  // a(n+1): viscosity, gravity
  half_kick(p.store, dt);                                  // v(n+1) = v(n+½) + a(n+1)·dt/2
  solve_and_record(p.store, p.hash, p.terrain, dt, /*divergence=*/true);  // divergence-free
}

double Dfsph::next_dt(const SphHealth& health) const {
  const SphSettings& s = settings_;
  double dt = s.dt_max / s.cfl_flow;
  if (health.v_max > 0) dt = std::min(dt, s.spacing / health.v_max);
  // Half the acoustic rule's factor on the acceleration: g dt²/dx = (cfl_flow/2)² = 0.04 at the
  // default. At cfl_flow² = 0.16 a column 16 particles deep compressed faster than the density
  // solve's Jacobi iterations caught up, and the run blew up in 6 steps.
  if (health.a_max > 0) dt = std::min(dt, 0.5 * std::sqrt(s.spacing / health.a_max));
  dt *= s.cfl_flow;
  const double nu = s.alpha_visc * s.c0 * s.h / 10.0;
  if (nu > 0) dt = std::min(dt, 0.125 * s.h * s.h / nu);
  return dt;
}

void Dfsph::solve_and_record(ParticleStore& store, const SpatialHash& hash, DeviceTerrain& terrain,
                             double dt, bool divergence) {
  const SolveResult r = solve(store, hash, terrain, dt, divergence);
  (divergence ? divergence_dt_ : density_dt_) = dt;
  SolveStats& s = divergence ? stats_.divergence : stats_.density;
  ++s.solves;
  s.iterations += static_cast<std::uint64_t>(r.iterations);
  s.last_error = r.mean_error;
  s.worst_error = r.worst_error;
  if (r.capped) {
    ++s.capped;
    caution(divergence ? "divergence-free" : "constant-density", r,
            divergence ? settings_.dfsph_divergence_error : settings_.dfsph_density_error);
  }
}

// One solve, Jacobi iterations of dfsph_pressure_acceleration and dfsph_density_change until the
// mean error of the particles in the solve is within the tolerance. The first pass measures the
// error without pressure: where no particle is compressed (a film, rain) the solve ends there.
Dfsph::SolveResult Dfsph::solve(ParticleStore& store, const SpatialHash& hash,
                                DeviceTerrain& terrain, double dt, bool divergence) {
  SolveResult r{0, false, 0.0, 0.0};
  const std::size_t n = store.size();
  if (n == 0) return r;
  const double dt_k = divergence ? dt : dt * dt;
  const double tolerance =
      0.01 * (divergence ? settings_.dfsph_divergence_error : settings_.dfsph_density_error);
  cl::Buffer& kappa = store.buffer(divergence ? kKappaV : kKappa);

  Kernel& change = density_change_;
  Kernel& accel = pressure_acceleration_;
  for (Kernel* k : {&change, &accel}) {
    bind_neighbourhood(*k, store, hash, terrain);
    k->set("pairs", pairs_).set("neighbour_count", store.spare(kListed));
    k->set("pair_image", pair_images_).set("planes", planes_);
  }
  store.bind(change, {kRho});
  change.set("factor", store.spare(kFactor)).set("theta", store.spare(kTheta));
  change.set("source", store.spare(kSource)).set("kappa", kappa);
  change.set("dt", static_cast<float>(dt)).set("dt_k", static_cast<float>(dt_k));
  change.set("error_scale", static_cast<float>(divergence ? dt : 1.0));
  change.set("divergence", cl_uint{divergence});
  const char* change_in[3] = {"ux", "uy", "uz"};
  if (divergence) {
    change.set("ux", store.buffer(kVx)).set("uy", store.buffer(kVy)).set("uz", store.buffer(kVz));
  } else {  // the drift's velocity without pressure, v + a·dt/2, in the spares of a(κ)
    launch_half_kick(
        store, dt,
        {&store.spare(kPressureAx), &store.spare(kPressureAx + 1), &store.spare(kPressureAx + 2)});
    for (int c = 0; c < 3; ++c) change.set(change_in[c], store.spare(kPressureAx + c));
  }
  std::tie(r.mean_error, r.worst_error) = density_change(store, /*iterate=*/false);
  if (r.mean_error <= tolerance) {
    // No pressure needed: none kept for the next step's warm start either.
    compute_.queue().enqueueFillBuffer(kappa, 0.0f, 0, n * sizeof(float));
    return r;
  }

  accel.set("kappa", kappa);
  const char* accel_out[3] = {"apx", "apy", "apz"};
  for (int c = 0; c < 3; ++c) {
    accel.set(accel_out[c], store.spare(kPressureAx + c));
    change.set(change_in[c], store.spare(kPressureAx + c));
  }
  while (true) {
    accel.launch(round_up_work(n));
    std::tie(r.mean_error, r.worst_error) = density_change(store, /*iterate=*/true);
    ++r.iterations;
    if (r.mean_error <= tolerance) break;
    if (r.iterations >= settings_.dfsph_max_iterations) {
      r.capped = true;
      break;
    }
  }
  store.bind(finish_, {kVx, kVy, kVz});
  for (int c = 0; c < 3; ++c) finish_.set(accel_out[c], store.spare(kPressureAx + c));
  finish_.set("kappa", kappa).set("dt", static_cast<float>(dt));
  finish_.set("dt_k", static_cast<float>(dt_k)).launch(round_up_work(n));
  return r;
}

std::pair<double, double> Dfsph::density_change(ParticleStore& store, bool iterate) {
  auto& q = compute_.queue();
  q.enqueueFillBuffer(errors_, cl_long{0}, 0, 2 * sizeof(cl_long));
  q.enqueueFillBuffer(error_max_, cl_uint{0}, 0, sizeof(cl_uint));
  density_change_.set("iterate", cl_uint{iterate});
  density_change_.set("errors", errors_).set("error_max", error_max_);
  density_change_.launch_groups((store.size() + kGroup - 1) / kGroup, kGroup);
  cl_long sums[2] = {0, 0};
  cl_uint worst_bits = 0;
  q.enqueueReadBuffer(errors_, CL_FALSE, 0, sizeof(sums), sums);
  q.enqueueReadBuffer(error_max_, CL_TRUE, 0, sizeof(worst_bits), &worst_bits);
  float worst = 0.0f;
  std::memcpy(&worst, &worst_bits, sizeof(worst));
  const double mean = sums[1] > 0 ? static_cast<double>(sums[0]) * kErrorQuantum / sums[1] : 0.0;
  return {mean, static_cast<double>(worst)};
}

void Dfsph::caution(const char* solve, const SolveResult& r, double tolerance) {
  if (cautioned_) return;  // once a run; the totals are in stats()
  cautioned_ = true;
  std::fprintf(stderr,
               "runnel: caution: the dfsph %s solve stopped at sph.dfsph_max_iterations = %d with "
               "a mean error of %.3g %% of rho0 (tolerance %.3g %%); the run goes on, and later "
               "solves that stop there are counted, not reported\n",
               solve, settings_.dfsph_max_iterations, 100.0 * r.mean_error, tolerance);
}

std::vector<float> Dfsph::pressure(ParticleStore& store) const {
  const std::vector<float> kappa = store.read_field(kKappa), kappa_v = store.read_field(kKappaV);
  std::vector<float> p(kappa.size(), 0.0f);
  for (std::size_t i = 0; i < p.size(); ++i) {
    double k = 0;
    if (density_dt_ > 0) k += kappa[i] / (density_dt_ * density_dt_);
    if (divergence_dt_ > 0) k += kappa_v[i] / divergence_dt_;
    p[i] = static_cast<float>(settings_.rho0 * k);
  }
  return p;
}

std::size_t Dfsph::bytes_per_particle() const {
  return kSlots * sizeof(cl_float4) + 4 * sizeof(cl_float) +
         (settings_.dfsph_floor_images ? kSlots * sizeof(cl_float) : 0);
}

std::size_t Dfsph::allocated_bytes() const {
  std::size_t bytes = 0;
  for (const cl::Buffer* b : {&pairs_, &planes_})
    if ((*b)() != nullptr) bytes += b->getInfo<CL_MEM_SIZE>();
  if (settings_.dfsph_floor_images && pair_images_() != nullptr)
    bytes += pair_images_.getInfo<CL_MEM_SIZE>();
  return bytes;
}

JsonObject Dfsph::json() const {
  JsonObject o;
  o.add("solver", "dfsph");
  for (const auto& [name, s] :
       {std::pair{"density", &stats_.density}, std::pair{"divergence", &stats_.divergence}}) {
    const std::string key(name);
    const double mean =
        s->solves > 0 ? static_cast<double>(s->iterations) / static_cast<double>(s->solves) : 0.0;
    o.add(key + "_solves", static_cast<long long>(s->solves))
        .add(key + "_iterations_mean", mean)
        .add(key + "_solves_capped", static_cast<long long>(s->capped))
        .add("last_" + key + "_error", s->last_error);
  }
  return o;
}

}  // namespace runnel
