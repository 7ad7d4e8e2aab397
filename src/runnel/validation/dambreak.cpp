// SPDX-License-Identifier: MIT
// Dam break (Koshizuka & Oka 1996): a column L wide and 2L high, released at t = 0 on a dry floor
// in a tank 4L long; a slab a few particles thick between free-slip front and back walls stands in
// for the 2-D experiment. The surge front (largest x of the fluid, + dx/2) is recorded every 0.05
// in t* = t·sqrt(g/L) up to 2.4 and compared with the measurements on what the flow produced, the
// surge distance s = (x − L)/L (the column's own width L is not a result):
//   error_k = |s_sim(t*_k) − s_exp(t*_k)| / s_exp(t*_k),
// at every measured time whose front lies inside the simulated tank (x_exp < 4L; the last
// measurement, 4.13 L, is beyond its wall). relative_error is their mean; the worst is reported
// too.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "runnel/io/atomic_file.hpp"
#include "runnel/io/plot.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel {

ValidationResult validate_dambreak(ComputeContext& compute, const ValidationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int resolution = options.resolution > 0 ? options.resolution : 20;  // particles across L
  const double L = 1.0;                                                     // m
  const double dx = L / resolution;
  const int slab = 4;  // particles through the slab
  Parameters params = options.params;
  params.set("sph.walls", true, "validate");
  const double g = params.real("sph.gravity");
  SphSettings s = SphSettings::from(params, dx, std::sqrt(g * 2.0 * L));

  const double tank_cell = slab * dx;
  SphSolver solver(compute, s, flat_floor(4 * resolution / slab, 1, tank_cell), 2.5 * L);
  solver.add(hydrostatic_block(s, L, 2.0 * L, slab * dx));
  const long long particles = static_cast<long long>(solver.particles().size());

  const double time_unit = std::sqrt(L / g);  // t = t*·sqrt(L/g)
  const double sample_every = 0.05, t_star_end = 2.4;
  std::vector<std::pair<double, double>> front;  // (t*, x/L)
  auto front_now = [&] {
    const HostParticles p = solver.particles().download();
    float x_max = 0;
    for (float x : p.f[kX]) x_max = std::max(x_max, x);
    return (x_max + 0.5 * dx) / L;
  };
  double prev_t = 0, prev_x = front_now();
  front.emplace_back(0.0, prev_x);
  int next_sample = 1;
  while (next_sample * sample_every <= t_star_end + 1e-9) {
    solver.step();
    const double t = solver.time() / time_unit, x = front_now();
    while (next_sample * sample_every <= t + 1e-12 &&
           next_sample * sample_every <= t_star_end + 1e-9) {
      const double ts = next_sample * sample_every;
      front.emplace_back(ts, prev_x + (x - prev_x) * (ts - prev_t) / (t - prev_t));
      ++next_sample;
    }
    prev_t = t;
    prev_x = x;
    if (options.progress) std::fprintf(stderr, "dambreak: t* = %.3f / %.1f\r", t, t_star_end);
  }
  if (options.progress) std::fprintf(stderr, "\n");

  auto interpolate = [&](double ts) {
    for (std::size_t k = 1; k < front.size(); ++k) {
      if (front[k].first >= ts) {
        const auto& a = front[k - 1];
        const auto& b = front[k];
        return a.second + (b.second - a.second) * (ts - a.first) / (b.first - a.first);
      }
    }
    return front.back().second;
  };
  const double tank = 4.0;  // L
  double error_sum = 0, worst = 0;
  int compared = 0;
  std::vector<JsonObject> table;
  std::vector<double> exp_t, exp_x;
  for (const auto& m : koshizuka_oka_1996()) {
    if (m.x_over_l >= tank) continue;
    const double x = interpolate(m.t_star);
    const double surge_exp = m.x_over_l - 1.0, surge_sim = x - 1.0;
    const double error = std::fabs(surge_sim - surge_exp) / surge_exp;
    error_sum += error;
    worst = std::max(worst, error);
    ++compared;
    exp_t.push_back(m.t_star);
    exp_x.push_back(m.x_over_l);
    table.push_back(JsonObject()
                        .add("t_star", m.t_star)
                        .add("x_over_L_experiment", m.x_over_l)
                        .add("x_over_L_runnel", x)
                        .add("surge_error", error));
  }

  if (!options.out_dir.empty()) {
    write_file_atomically((std::filesystem::path(options.out_dir) / "front.csv").string(),
                          [&](std::FILE* f) {
                            std::fprintf(f, "t_star,x_over_L\n");
                            for (auto& [ts, x] : front) std::fprintf(f, "%.2f,%.6f\n", ts, x);
                          });
    std::vector<double> sim_t, sim_x;
    for (auto& [ts, x] : front) sim_t.push_back(ts), sim_x.push_back(x);
    Plot plot("dam break: surge front", "t* = t sqrt(g/L)", "x/L");
    plot.points(exp_t, exp_x, kPlotReference, "koshizuka & oka 1996");
    plot.line(sim_t, sim_x, kPlotSimulation,
              "runnel, " + std::to_string(resolution) + " particles across l");
    plot.write((std::filesystem::path(options.out_dir) / "front.png").string());
  }
  ValidationResult r;
  r.name = "dambreak";
  r.particles = particles;
  r.steps = static_cast<long long>(solver.steps());
  r.relative_error = error_sum / compared;
  r.target = 0.10;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.details.add("resolution", resolution)
      .add("dx", dx)
      .add("L", L)
      .add("c0", s.c0)
      .add("sim_time", solver.time())
      .add("manning_n", s.manning_n)
      .add("compared_points", compared)
      .add("worst_surge_error", worst)
      .add("measure", "surge distance (x - L)/L, relative to the experiment's")
      .add("front", table)
      .add("reference", "Koshizuka & Oka 1996");
  return r;
}

}  // namespace runnel
