// SPDX-License-Identifier: MIT
// runnel validate mobile-bed: the pipe model in the flume of Soares-Frazão et al. (2012), scored
// against the gauges and the final bed of the experiment's four repeats.
#include "runnel/validation/mobile_bed.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel {

namespace {

constexpr double kTarget = 0.03;  // m: the experiment's worst scatter, the case's tolerance
constexpr double kSandSurface = 0.085, kArrivalRise = 0.02;

// y(x) by linear interpolation on increasing x; NaN outside [x.front(), x.back()].
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.empty() || at < x.front() || at > x.back()) return std::nan("");
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  if (it == x.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(it - x.begin());
  if (k == 0) return y.front();
  const double w = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

// The first time a level series reaches the sand surface + 2 cm (NaN if never).
double arrival(const std::vector<double>& t, const std::vector<double>& level) {
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (level[k] < kSandSurface + kArrivalRise) continue;
    if (k == 0) return t[0];
    const double w = (kSandSurface + kArrivalRise - level[k - 1]) / (level[k] - level[k - 1]);
    return t[k - 1] + w * (t[k] - t[k - 1]);
  }
  return std::nan("");
}

struct Series {
  std::vector<double> t, surface;
};

// probes.csv as series by gauge name.
std::map<std::string, Series> read_probes(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw runtime_error(path + ": the run wrote no gauge readings");
  std::map<std::string, Series> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string t, name, surface;
    std::getline(row, t, ',');
    std::getline(row, name, ',');
    std::getline(row, surface, ',');
    out[name].t.push_back(std::stod(t));
    out[name].surface.push_back(std::stod(surface));
  }
  return out;
}

struct GaugeScore {
  std::string name;
  Series simulated;  // the mirrored pair averaged
  double rmse = 0, bias = 0, arrival_simulated = 0, arrival_measured = 0;
};

GaugeScore score_gauge(const MobileBedGauge& g, const std::map<std::string, Series>& probes) {
  GaugeScore s;
  s.name = g.name;
  const Series& a = probes.at(g.name);
  const Series& b = probes.at(g.name + "_mirror");
  s.simulated.t = a.t;
  for (std::size_t k = 0; k < a.t.size(); ++k)
    s.simulated.surface.push_back(0.5 * (a.surface[k] + b.surface[k]));
  double sum2 = 0, sum = 0;
  for (std::size_t k = 0; k < g.t.size(); ++k) {
    const double e = interpolate(s.simulated.t, s.simulated.surface, g.t[k]) - g.surface[k];
    sum2 += e * e;
    sum += e;
  }
  s.rmse = std::sqrt(sum2 / g.t.size());
  s.bias = sum / g.t.size();
  s.arrival_simulated = arrival(s.simulated.t, s.simulated.surface);
  s.arrival_measured = arrival(g.t, g.surface);
  return s;
}

struct ProfileScore {
  std::string name;
  std::vector<double> x, simulated, low, high, mean;
  double rmse_band = 0, worst_band = 0, rmse_mean = 0;
  double rmse_band_unmoved = 0;  // the same score for the bed as it started: what no erosion gets
};

ProfileScore score_profile(const MobileBedProfile& p, const Heightmap& bed,
                           const Heightmap& initial) {
  ProfileScore s;
  s.name = p.name;
  const MapFrame map(bed);
  std::vector<double> xs;
  for (const auto& r : p.repeats) xs.insert(xs.end(), r.x.begin(), r.x.end());
  std::sort(xs.begin(), xs.end());
  double sum_band = 0, sum_mean = 0, sum_unmoved = 0;
  auto along = [&](const Heightmap& h, double x) {
    return 0.5 * (surface_height(h, map.world_x(x), map.world_z(p.y)) +
                  surface_height(h, map.world_x(x), map.world_z(-p.y)));
  };
  for (double x : xs) {
    double low = 1e9, high = -1e9, total = 0;
    int n = 0;
    for (const auto& r : p.repeats) {
      const double z = interpolate(r.x, r.z, x);
      if (std::isnan(z)) continue;
      low = std::min(low, z), high = std::max(high, z), total += z, ++n;
    }
    if (n < 2) continue;  // a band needs two repeats
    const double z = along(bed, x);
    const double unmoved = outside_band(along(initial, x), low, high);
    sum_unmoved += unmoved * unmoved;
    s.x.push_back(x), s.simulated.push_back(z), s.low.push_back(low), s.high.push_back(high);
    s.mean.push_back(total / n);
    const double e = outside_band(z, low, high);
    sum_band += e * e, sum_mean += (z - total / n) * (z - total / n);
    s.worst_band = std::max(s.worst_band, e);
  }
  s.rmse_band = std::sqrt(sum_band / std::max<std::size_t>(1, s.x.size()));
  s.rmse_mean = std::sqrt(sum_mean / std::max<std::size_t>(1, s.x.size()));
  s.rmse_band_unmoved = std::sqrt(sum_unmoved / std::max<std::size_t>(1, s.x.size()));
  return s;
}

// The deepest scour below the gate (0 ≤ x ≤ 1.5 m) and the deposit's crest (1.5 < x ≤ 8 m) along
// a profile: the sand surface less the lowest bed, and the highest bed less the sand surface.
std::pair<double, double> scour_and_crest(const std::vector<double>& x,
                                          const std::vector<double>& z) {
  double lowest = kSandSurface, highest = kSandSurface;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] >= 0 && x[k] <= 1.5) lowest = std::min(lowest, z[k]);
    if (x[k] > 1.5 && x[k] <= 8) highest = std::max(highest, z[k]);
  }
  return {kSandSurface - lowest, highest - kSandSurface};
}

// gauges.csv (each gauge's water surface over time, measured and simulated, a row a sample) and
// profiles.csv (each final bed profile beside the repeats' band and mean, a row a point): what
// runnel.plot draws (`python -m runnel plot OUT`).
void write_tables(const std::filesystem::path& out, const std::string& model,
                  const std::vector<GaugeScore>& gauges,
                  const std::vector<ProfileScore>& profiles) {
  write_file_atomically((out / "gauges.csv").string(), [&](std::FILE* f) {
    std::fprintf(f, "gauge,x,y,source,t,surface\n");
    for (std::size_t g = 0; g < gauges.size(); ++g) {
      const MobileBedGauge& m = soares_frazao_gauges()[g];
      for (std::size_t k = 0; k < m.t.size(); ++k)
        std::fprintf(f, "%s,%g,%g,measured,%.6g,%.6g\n", m.name.c_str(), m.x, m.y, m.t[k],
                     m.surface[k]);
      const Series& run = gauges[g].simulated;
      for (std::size_t k = 0; k < run.t.size(); ++k)
        std::fprintf(f, "%s,%g,%g,%s,%.6g,%.6g\n", m.name.c_str(), m.x, m.y, model.c_str(),
                     run.t[k], run.surface[k]);
    }
  });
  write_file_atomically((out / "profiles.csv").string(), [&](std::FILE* f) {
    std::fprintf(f, "profile,y,x,low,high,mean,model,simulated\n");
    for (std::size_t p = 0; p < profiles.size(); ++p) {
      const ProfileScore& s = profiles[p];
      for (std::size_t k = 0; k < s.x.size(); ++k)
        std::fprintf(f, "%s,%g,%.6g,%.6g,%.6g,%.6g,%s,%.6g\n", s.name.c_str(),
                     soares_frazao_profiles()[p].y, s.x[k], s.low[k], s.high[k], s.mean[k],
                     model.c_str(), s.simulated[k]);
    }
  });
}

}  // namespace

ValidationResult validate_mobile_bed(ComputeContext& compute, const ValidationOptions& options) {
  namespace fs = std::filesystem;
  const int per_metre = options.resolution > 0 ? options.resolution : 20;
  const double cell = 1.0 / per_metre;
  const fs::path out =
      options.out_dir.empty()
          ? fs::temp_directory_path() / ("runnel-mobile-bed-" + std::to_string(::getpid()))
          : fs::path(options.out_dir);
  const std::string scenario = (out / "flume" / "scenario.toml").string();
  write_flume_scenario(soares_frazao_flume(cell), (out / "flume").string(), scenario);
  Parameters params = load_scenario(scenario);
  for (const auto& [key, value] : options.params.values())
    if (options.params.was_set(key)) params.set(key, value, "--set");
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Model> model = make_model(compute, params, load_terrain(params));
  RunOptions run = run_options_from(params, model->info().clock);
  run.out_dir = (out / model->info().name).string();
  run.quiet = !options.progress;
  run.overwrite = true;
  const RunSummary summary = run_model(compute, *model, run);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const auto probes = read_probes((out / model->info().name / "probes.csv").string());
  std::vector<GaugeScore> gauges;
  for (const MobileBedGauge& g : soares_frazao_gauges()) gauges.push_back(score_gauge(g, probes));
  const Heightmap bed = model->terrain();
  std::vector<ProfileScore> profiles;
  for (const MobileBedProfile& p : soares_frazao_profiles())
    profiles.push_back(score_profile(p, bed, model->initial_terrain()));
  write_tables(out, model->info().name, gauges, profiles);

  double worst = 0;
  std::vector<JsonObject> gauge_json, profile_json;
  for (const GaugeScore& g : gauges) {
    worst = std::max(worst, g.rmse / kTarget);
    gauge_json.push_back(JsonObject()
                             .add("gauge", g.name)
                             .add("rmse_m", g.rmse)
                             .add("bias_m", g.bias)
                             .add("arrival_s", g.arrival_simulated)
                             .add("arrival_measured_s", g.arrival_measured));
  }
  for (const ProfileScore& p : profiles) {
    worst = std::max(worst, p.rmse_band / kTarget);
    profile_json.push_back(JsonObject()
                               .add("profile", p.name)
                               .add("rmse_to_band_m", p.rmse_band)
                               .add("worst_to_band_m", p.worst_band)
                               .add("rmse_to_mean_m", p.rmse_mean)
                               .add("rmse_to_band_unmoved_bed_m", p.rmse_band_unmoved));
  }
  const auto [scour, crest] = scour_and_crest(profiles[0].x, profiles[0].simulated);
  const auto [scour_measured, crest_measured] = scour_and_crest(profiles[0].x, profiles[0].mean);
  ValidationResult r;
  r.name = "mobile-bed";
  r.steps = static_cast<long long>(summary.steps);
  r.wall_seconds = wall;
  r.relative_error = worst;  // the worst RMSE in units of the 3-cm tolerance
  r.target = 1.0;
  r.details = JsonObject()
                  .add("model", model->info().name)
                  .add("cell_m", cell)
                  .add("sim_time_s", model->time())
                  .add("mass_balance_residual_quanta",
                       static_cast<long long>(summary.balance.residual_quanta))
                  .add("tolerance_m", kTarget)
                  .add("gauges", gauge_json)
                  .add("profiles", profile_json)
                  .add("scour_below_gate_m", scour)
                  .add("scour_below_gate_measured_m", scour_measured)
                  .add("deposit_crest_m", crest)
                  .add("deposit_crest_measured_m", crest_measured);
  if (options.out_dir.empty()) fs::remove_all(out);
  return r;
}

}  // namespace runnel
