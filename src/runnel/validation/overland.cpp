// SPDX-License-Identifier: MIT
#include "runnel/validation/overland.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/hydrograph.hpp"
#include "runnel/terrain/probes.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

constexpr double kGravity = 9.81;
// The targets (docs/validation.md, "Overland flow").
constexpr double kGridDepthTarget = 0.10;       // depths at equilibrium, away from the last metre
constexpr double kGridOutflowTarget = 0.05;     // the hydrograph at every time, of i·A
constexpr double kGridStorageTarget = 0.05;     // the water on the plane at equilibrium
constexpr double kSphDepthTarget = 0.15;        // where at least three particles deep
constexpr double kSphEquilibriumTarget = 0.02;  // the outflow at equilibrium against i·A
constexpr double kSphRiseTarget = 0.15;         // the time the outflow reaches 95 % of i·A
// Rows of the hydrograph per t_e, and the share of t_e before the rain stops that is averaged as
// the equilibrium.
constexpr double kRowsPerEquilibriumTime = 40;
constexpr double kEquilibriumWindow = 0.25;

bool is_sph(const std::string& run) {
  return run == "wcsph" || run == "dfsph";
}

// The plane on the terrain's grid: column 0, row 0 and the rows below the plane's are walls, the
// plane's rows 1 … rows run from column 1 to the open east edge. A grid cell is centred on its
// vertex, so the rained plane starts at x = cell/2 and ends at the edge, (nx − 1/2)·cell: its
// length is (nx − 1)·cell. The terrain has at least 16 rows (the SPH model's smallest terrain);
// rows past the plane's second wall are more wall.
struct PlaneGrid {
  int nx = 0, ny = 0, rows = 0;
  double cell = 0;
  double length() const { return (nx - 1) * cell; }
  double width() const { return rows * cell; }
  bool walled(int i, int j) const { return i == 0 || j == 0 || j > rows; }
  double world_x(double x) const { return x + 0.5 * cell; }  // from the upstream wall's face
};

PlaneGrid plane_grid(const OverlandCase& c) {
  PlaneGrid g;
  g.cell = c.cell;
  g.nx = static_cast<int>(std::lround(c.length / c.cell)) + 1;
  g.rows = static_cast<int>(std::lround(c.width / c.cell));
  g.ny = std::max(g.rows + 2, 16);
  return g;
}

Heightmap plane_terrain(const PlaneGrid& g, double slope, double wall) {
  Heightmap t(g.nx, g.ny, g.cell);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double bed = 1.0 + slope * (g.nx - 1 - i) * g.cell;
      t.h[static_cast<std::size_t>(j) * g.nx + i] =
          static_cast<float>(bed + (g.walled(i, j) ? wall : 0));
    }
  return t;
}

// Rain on the plane only: a mask of 1 inside the walls, 0 on them.
Heightmap plane_rain_mask(const PlaneGrid& g) {
  Heightmap m(g.nx, g.ny, g.cell, 0.0f);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (!g.walled(i, j)) m.h[static_cast<std::size_t>(j) * g.nx + i] = 1.0f;
  return m;
}

Parameters run_parameters(const OverlandCase& c, const std::string& run, double spacing,
                          const std::string& rain_mask) {
  Parameters p = default_parameters();
  const KinematicPlane plane = c.plane();
  p.set("run.seed", std::int64_t{1}, "overland");
  p.set("ground.rain_mask", rain_mask, "overland");
  // Nothing erodes: the walls would otherwise slump onto the plane at the talus angle.
  p.set("thermal.interval", 0.0, "overland");
  if (is_sph(run)) {
    p.set("run.model", std::string("sph"), "overland");
    p.set("sph.solver", run, "overland");
    p.set("sph.spacing", spacing, "overland");
    p.set("sph.manning_n", c.manning_n, "overland");
    p.set("sph.walls", false, "overland");
    p.set("rain.intensity", c.rain_mm_h, "overland");
    p.set("erosion.erodibility", 0.0, "overland");
  } else {
    p.set("run.model", std::string("pipe"), "overland");
    p.set("pipe.flux", run, "overland");
    p.set("pipe.manning_n", c.manning_n, "overland");
    p.set("pipe.rain", plane.rain, "overland");
    p.set("pipe.edges", std::string("outflow"), "overland");
    for (const char* key : {"pipe.evaporation", "pipe.capacity", "pipe.dissolve", "pipe.deposit"})
      p.set(key, 0.0, "overland");
  }
  for (const auto& [key, value] : c.params.values())
    if (c.params.was_set(key)) p.set(key, value, "--set");
  return p;
}

// The mean depth across the plane's rows at distance x down the plane.
double depth_across(const Heightmap& bed, const std::vector<float>& depth, const PlaneGrid& g,
                    double x) {
  double sum = 0;
  for (int j = 1; j <= g.rows; ++j)
    sum += read_probe(bed, depth, Probe{"", g.world_x(x), j * g.cell}).depth;
  return sum / g.rows;
}

// The analytic outflow per unit width averaged over [t0, t1] (Simpson's rule on 16 pieces; the
// hydrograph's kinks make a piece's error at most a few 10⁻⁴ of i·L).
double mean_outflow(const KinematicPlane& plane, double t0, double t1) {
  if (!(t1 > t0)) return plane.outflow(t1);
  const int pieces = 16;
  const double h = (t1 - t0) / pieces;
  double sum = plane.outflow(t0) + plane.outflow(t1);
  for (int k = 1; k < pieces; ++k) sum += (k % 2 ? 4 : 2) * plane.outflow(t0 + k * h);
  return sum * h / 3 / (t1 - t0);
}

struct BudgetRow {
  double t;
  WaterBudget budget;
};

struct RunRecord {
  std::string name;
  double spacing = 0;
  std::vector<BudgetRow> rows;
  std::vector<double> gauge_x, gauge_depth;  // the equilibrium depths (window means)
  long long steps = 0;
  double wall_seconds = 0;
  double bed_moved = 0;  // Σ |Δh| · cell² at the end (m³): the case assumes a fixed bed
  std::string caution;   // the model's own, when it ran outside what it holds
  std::vector<std::pair<std::string, double>> model_values;  // Model::summary_values()
};

RunRecord run_case(ComputeContext& compute, const OverlandCase& c, const PlaneGrid& g,
                   const Heightmap& terrain, const std::string& run, double spacing,
                   const std::string& rain_mask, const std::vector<double>& gauges) {
  const KinematicPlane plane = c.plane();
  const double te = plane.equilibrium_time();
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Model> model =
      make_model(compute, run_parameters(c, run, spacing, rain_mask), terrain);
  RunRecord r;
  r.name = run;
  r.spacing = spacing;
  r.gauge_x = gauges;
  r.gauge_depth.assign(gauges.size(), 0.0);
  const double every = te / kRowsPerEquilibriumTime;
  Hydrograph hydrograph(every, false, 0.0, *model->water_budget());
  int window_samples = 0;
  auto after_step = [&] {
    const double t = model->time();
    if (!hydrograph.due(t)) return;
    const WaterBudget b = *model->water_budget();
    hydrograph.record(t, b);
    r.rows.push_back({t, b});
    if (t >= plane.duration - kEquilibriumWindow * te - 1e-9 && t <= plane.duration + 1e-9) {
      const Heightmap bed = model->terrain();
      const std::vector<float> depth = model->interaction().water_view().depth;
      for (std::size_t k = 0; k < gauges.size(); ++k)
        r.gauge_depth[k] += depth_across(bed, depth, g, gauges[k]);
      ++window_samples;
    }
  };
  if (c.progress)
    std::fprintf(stderr, "runnel: overland: %s%s ...\n", run.c_str(),
                 is_sph(run) ? (" at " + format_number(spacing) + " m").c_str() : "");
  model->advance(plane.duration, after_step);
  model->interaction().set_global_rain(false);
  model->advance(c.recession > 0 ? c.recession : te, after_step);
  for (double& d : r.gauge_depth) d /= std::max(window_samples, 1);
  const Heightmap before = model->initial_terrain(), after = model->terrain();
  for (std::size_t k = 0; k < before.h.size(); ++k)
    r.bed_moved += std::fabs(static_cast<double>(after.h[k]) - before.h[k]) * g.cell * g.cell;
  r.steps = static_cast<long long>(model->steps());
  r.caution = model->caution();
  r.model_values = model->summary_values();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!c.out_dir.empty()) {
    const std::filesystem::path dir =
        std::filesystem::path(c.out_dir) / (is_sph(run) ? run + "-" + format_number(spacing) : run);
    std::filesystem::create_directories(dir);
    write_text_atomically((dir / "outflow.csv").string(), hydrograph.csv());
  }
  return r;
}

struct RunScore {
  double depth_worst = 0, depth_mean = 0;
  int depth_gauges = 0;
  double outflow_worst = 0, outflow_mean = 0;  // of i·A
  double equilibrium = 0;                      // mean outflow in the window / (i·A) − 1
  double storage = 0;                          // stored at the rain's end / analytic − 1
  double rise = 0, rise_time = -1;             // t95's relative error, and t95 (s)
  double balance = 0;                          // (rain − outflow − stored) / rain at the end
  bool meets = false;
  std::vector<double> depth_errors;
};

RunScore score(const OverlandCase& c, const PlaneGrid& g, const RunRecord& r) {
  const KinematicPlane plane = c.plane();
  const double te = plane.equilibrium_time(), W = g.width(), iA = plane.rain * W * plane.length;
  RunScore s;
  const double deep = 3 * r.spacing;  // SPH: gauges with at least three particles of depth
  for (std::size_t k = 0; k < r.gauge_x.size(); ++k) {
    const double exact = plane.equilibrium_depth(r.gauge_x[k]);
    const double e = r.gauge_depth[k] / exact - 1;
    s.depth_errors.push_back(e);
    if (is_sph(r.name) && exact < deep) continue;
    s.depth_worst = std::max(s.depth_worst, std::fabs(e));
    s.depth_mean += std::fabs(e);
    ++s.depth_gauges;
  }
  if (s.depth_gauges > 0) s.depth_mean /= s.depth_gauges;
  double window_out = 0, window_span = 0;
  const double t95 = std::pow(0.95 * plane.rain * plane.length / plane.alpha(), 0.6) / plane.rain;
  for (std::size_t k = 1; k < r.rows.size(); ++k) {
    const double t0 = r.rows[k - 1].t, t1 = r.rows[k].t, span = t1 - t0;
    const double q = (r.rows[k].budget.outflow - r.rows[k - 1].budget.outflow) / span;
    const double e = std::fabs(q - W * mean_outflow(plane, t0, t1)) / iA;
    s.outflow_worst = std::max(s.outflow_worst, e);
    s.outflow_mean += e;
    if (t0 >= plane.duration - kEquilibriumWindow * te - 1e-9 && t1 <= plane.duration + 1e-9) {
      window_out += q * span;
      window_span += span;
    }
    if (s.rise_time < 0 && q >= 0.95 * iA) {
      const double q0 = k > 1 ? (r.rows[k - 1].budget.outflow - r.rows[k - 2].budget.outflow) /
                                    (t0 - r.rows[k - 2].t)
                              : 0.0;
      // Each mean stands at its interval's middle; between two middles, linearly.
      const double m0 = k > 1 ? 0.5 * (r.rows[k - 2].t + t0) : 0.0, m1 = 0.5 * (t0 + t1);
      s.rise_time = q > q0 ? m0 + (0.95 * iA - q0) / (q - q0) * (m1 - m0) : m1;
    }
  }
  if (r.rows.size() > 1) s.outflow_mean /= static_cast<double>(r.rows.size() - 1);
  s.equilibrium = window_span > 0 ? window_out / window_span / iA - 1 : -1;
  s.rise = s.rise_time > 0 ? s.rise_time / t95 - 1 : 1;
  for (const BudgetRow& row : r.rows)
    if (row.t <= plane.duration + 1e-9)
      s.storage = row.budget.stored / (W * plane.storage(row.t)) - 1;
  if (!r.rows.empty()) {
    const WaterBudget& b = r.rows.back().budget;
    s.balance = b.rain > 0 ? (b.rain - b.outflow - b.stored) / b.rain : 0;
  }
  s.meets = is_sph(r.name)
                ? s.depth_gauges > 0 && s.depth_worst <= kSphDepthTarget &&
                      std::fabs(s.equilibrium) <= kSphEquilibriumTarget &&
                      std::fabs(s.rise) <= kSphRiseTarget
                : s.depth_worst <= kGridDepthTarget && s.outflow_worst <= kGridOutflowTarget &&
                      std::fabs(s.storage) <= kGridStorageTarget;
  return s;
}

// What names a run in the JSON, scored or failed: the run, its model and, for SPH, the spacing.
JsonObject run_header(const std::string& run, double spacing) {
  JsonObject o;
  o.add("run", run);
  o.add("model", is_sph(run) ? "sph" : "pipe");
  if (is_sph(run)) o.add("spacing_m", spacing);
  return o;
}

JsonObject model_values_json(const std::vector<std::pair<std::string, double>>& values) {
  JsonObject o;
  for (const auto& [name, value] : values) o.add(name, value);
  return o;
}

JsonObject run_json(const RunRecord& r, const RunScore& s) {
  std::vector<JsonObject> gauges;
  for (std::size_t k = 0; k < r.gauge_x.size(); ++k)
    gauges.push_back(JsonObject()
                         .add("x_m", r.gauge_x[k])
                         .add("depth_m", r.gauge_depth[k])
                         .add("error", s.depth_errors[k]));
  JsonObject run = run_header(r.name, r.spacing);
  if (!r.caution.empty()) run.add("caution", r.caution);
  return run.add("steps", r.steps)
      .add("wall_seconds", r.wall_seconds)
      .add("depth_worst_error", s.depth_worst)
      .add("depth_mean_error", s.depth_mean)
      .add("depth_gauges_scored", static_cast<long long>(s.depth_gauges))
      .add("outflow_worst_error_of_iA", s.outflow_worst)
      .add("outflow_mean_error_of_iA", s.outflow_mean)
      .add("equilibrium_outflow_error", s.equilibrium)
      .add("storage_error", s.storage)
      .add("rise_time_95_s", s.rise_time)
      .add("rise_time_95_error", s.rise)
      .add("water_balance_rel", s.balance)
      .add("bed_moved_m3", r.bed_moved)
      .merge(model_values_json(r.model_values))
      .add("meets_targets", s.meets)
      .add("gauges", gauges);
}

}  // namespace

const std::vector<std::string>& overland_run_names() {
  static const std::vector<std::string> names = {"pipes", "local-inertial", "godunov", "wcsph",
                                                 "dfsph"};
  return names;
}

KinematicPlane OverlandCase::plane() const {
  KinematicPlane p;
  const PlaneGrid g = plane_grid(*this);
  p.length = g.length();
  p.slope = slope;
  p.manning_n = manning_n;
  p.rain = rain_mm_h / 3.6e6;
  p.duration = 1.0;  // resolved below from t_e
  p.duration = duration > 0 ? duration : 2 * p.equilibrium_time();
  return p;
}

void OverlandCase::check() const {
  auto positive = [](const char* flag, double v, double most) {
    if (!(v > 0 && v <= most))
      throw input_error(std::string(flag) + ": must be more than 0 and at most " +
                        format_number(most) + " (got " + format_number(v) + ")");
  };
  positive("--length", length, 1e5);
  positive("--width", width, 1e4);
  positive("--slope", slope, 1);
  positive("--manning-n", manning_n, 1);
  positive("--rain", rain_mm_h, 1e7);
  positive("--cell", cell, 100);
  if (!(duration >= 0) || !(recession >= 0))
    throw input_error("--duration, --recession: must not be negative");
  if (length / cell < 4 || width / cell < 1)
    throw input_error("--cell: " + format_number(cell) +
                      " m leaves fewer than 4 cells along or 1 across the plane");
  if (length / cell * (width / cell + 2) > 2e7)
    throw input_error("--cell: " + format_number(cell) + " m makes a grid of over 2·10⁷ cells");
  for (const std::string& run : runs)
    if (std::find(overland_run_names().begin(), overland_run_names().end(), run) ==
        overland_run_names().end())
      throw input_error("--models: unknown run '" + run +
                        "' (pipes, local-inertial, godunov, wcsph or dfsph)");
  const KinematicPlane p = plane();
  if (duration > 0 && duration < p.equilibrium_time())
    throw input_error("--duration: " + format_number(duration) +
                      " s ends the rain before equilibrium (t_e = " +
                      format_number(p.equilibrium_time()) + " s)");
  const double k = p.kinematic_number(kGravity);
  if (k < 3)
    throw input_error(
        "the plane is outside the kinematic wave: kinematic number k = L g n^2 / "
        "h_L^(4/3) = " +
        format_number(k) +
        " (at least 3; 10 for a close match): make it longer, rougher or the rain lighter");
  const bool has_sph = std::any_of(runs.begin(), runs.end(), is_sph);
  const double foot = p.equilibrium_depth(p.length);
  for (double s : spacings) {
    positive("--spacing", s, 10);
    if (has_sph && foot < 2 * s)
      throw input_error("--spacing: " + format_number(s) +
                        " m puts fewer than two particles in the "
                        "depth at the foot (" +
                        format_number(foot) + " m): at most " + format_number(foot / 2) + " m");
  }
}

JsonObject validate_overland(ComputeContext& compute, const OverlandCase& c) {
  namespace fs = std::filesystem;
  c.check();
  const KinematicPlane plane = c.plane();
  const PlaneGrid g = plane_grid(c);
  const double foot = plane.equilibrium_depth(plane.length);
  const Heightmap terrain = plane_terrain(g, c.slope, std::max(1.0, 4 * foot));
  const fs::path scratch = c.out_dir.empty() ? fs::temp_directory_path() /
                                                   ("runnel-overland-" + std::to_string(::getpid()))
                                             : fs::path(c.out_dir);
  fs::create_directories(scratch);
  const std::string rain_mask = (scratch / "rain_mask.asc").string();
  write_terrain(rain_mask, plane_rain_mask(g));
  // Gauges every tenth of the plane, none in the last metre (the drawdown to the brink there is
  // physical, and outside the kinematic wave).
  std::vector<double> gauges;
  for (int k = 1; k <= 9; ++k)
    if (plane.length * k / 10 <= plane.length - 1.0) gauges.push_back(plane.length * k / 10);
  std::vector<RunRecord> records;
  std::vector<JsonObject> runs;
  bool all = true;
  for (const std::string& run : c.runs) {
    const std::vector<double> spacings = is_sph(run) ? c.spacings : std::vector<double>{0.0};
    for (double s : spacings) {
      // A run that stops (a numerical blow-up) is a result too: it is reported as failed, with
      // its reason, and the other runs go on. Bad input still ends the command.
      try {
        records.push_back(run_case(compute, c, g, terrain, run, s, rain_mask, gauges));
      } catch (const Error& e) {
        if (e.code() != ExitCode::kRuntime) throw;
        std::fprintf(stderr, "runnel: overland: %s%s stopped: %s\n", run.c_str(),
                     is_sph(run) ? (" at " + format_number(s) + " m").c_str() : "", e.what());
        all = false;
        runs.push_back(
            run_header(run, s).add("error", std::string(e.what())).add("meets_targets", false));
        continue;
      }
      const RunScore sc = score(c, g, records.back());
      all = all && sc.meets;
      runs.push_back(run_json(records.back(), sc));
    }
  }
  JsonObject o = JsonObject()
                     .add("case", "overland")
                     .add("length_m", plane.length)
                     .add("width_m", g.width())
                     .add("slope", plane.slope)
                     .add("manning_n", plane.manning_n)
                     .add("rain_mm_h", c.rain_mm_h)
                     .add("rain_duration_s", plane.duration)
                     .add("cell_m", g.cell)
                     .add("equilibrium_time_s", plane.equilibrium_time())
                     .add("foot_depth_m", foot)
                     .add("kinematic_number", plane.kinematic_number(kGravity))
                     .add("runs", runs)
                     .add("all_targets_met", all);
  if (c.out_dir.empty()) {
    fs::remove_all(scratch);
  } else {
    // The scores beside the runs' outflow.csv: runnel.plot draws the hydrographs and the depths
    // beside the kinematic wave from them (`python -m runnel plot OUT`).
    write_text_atomically((scratch / "overland.json").string(), o.str() + "\n");
  }
  return o;
}

}  // namespace runnel
