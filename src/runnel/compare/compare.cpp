// SPDX-License-Identifier: MIT
#include "runnel/compare/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "runnel/core/error.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/models/droplet_model.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/terrain/standing_water.hpp"

namespace runnel::compare {

RainBudget rain_budget(ComputeContext& compute, const Parameters& params,
                       const Heightmap& terrain) {
  Parameters sph = params;
  sph.set("run.model", std::string("sph"), "compare");
  // The SPH model resolves its automatic rain (rate from the particle budget and lifespan,
  // spacing from the cell) exactly as its run will.
  SphModel model(compute, sph, terrain);
  RainBudget b;
  const double spacing = model.particle_spacing();
  b.particle_volume = spacing * spacing * spacing;
  b.duration = params.real("run.sim_time");
  b.sph_rate = model.rain().enabled ? model.rain().rate : 0.0;
  b.volume = b.sph_rate * b.particle_volume * b.duration;
  return b;
}

Parameters model_parameters(const Parameters& scenario, const std::string& model,
                            const RainBudget& budget, const Heightmap& terrain) {
  Parameters p = scenario;
  p.set("run.model", model, "compare");
  const double area = static_cast<double>(terrain.size()) * terrain.cell * terrain.cell;
  if (model == "pipe") {
    p.set("pipe.rain", budget.volume / (area * budget.duration), "compare");
  } else if (model == "olsen") {
    const double iterations = static_cast<double>(p.integer("run.iterations"));
    p.set("olsen.rain", budget.volume / (area * iterations), "compare");
  } else if (model == "droplet") {
    const long long droplets =
        std::max<long long>(1, std::llround(budget.volume / budget.particle_volume));
    const long long batch =
        DropletSettings::from(p).batch_for(static_cast<long long>(terrain.size()));
    const long long iterations = (droplets + batch - 1) / batch;
    p.set("droplet.volume", budget.particle_volume, "compare");
    p.set("droplet.batch", static_cast<std::int64_t>((droplets + iterations - 1) / iterations),
          "compare");
    p.set("run.iterations", static_cast<std::int64_t>(iterations), "compare");
  }
  return p;
}

namespace {

// The keys model_parameters may set, as "key = value, ..." where they differ from the scenario.
std::string setup_text(const Parameters& scenario, const Parameters& p) {
  std::string out;
  for (const char* key :
       {"pipe.rain", "olsen.rain", "droplet.volume", "droplet.batch", "run.iterations"}) {
    const std::string value = Parameters::to_text(p.values().at(key));
    if (value != Parameters::to_text(scenario.values().at(key)))
      out += (out.empty() ? "" : ", ") + std::string(key) + " = " + value;
  }
  return out;
}

std::vector<Parameters> checked_parameters(ComputeContext& compute, const Parameters& scenario,
                                           const Heightmap& terrain, const Options& options,
                                           RainBudget& budget) {
  if (options.models.empty()) throw input_error("--models: name at least one model");
  std::set<std::string> seen;
  for (const std::string& m : options.models) {
    if (m.empty()) throw input_error("--models: an empty name in the list");
    model_entry(m);  // an unknown name: exit 2, listing the models
    if (!seen.insert(m).second) throw input_error("--models: " + m + " is listed twice");
  }
  if (scenario.integer("run.steps") > 0) {
    throw input_error(
        "run.steps: runnel compare runs every model for run.sim_time seconds (iteration models "
        "for run.iterations); set run.steps to 0");
  }
  if (!(scenario.real("run.sim_time") > 0))
    throw input_error("run.sim_time: must be positive for runnel compare");
  budget = rain_budget(compute, scenario, terrain);
  // Without rain the models compare on the scenario's standing water alone (a dam break).
  if (!(budget.volume > 0) && !has_standing_water(scenario))
    throw input_error(
        "rain.enabled: runnel compare needs rain or standing water (the rain budget is 0 m3)");
  std::vector<Parameters> out;
  for (const std::string& m : options.models) {
    out.push_back(model_parameters(scenario, m, budget, terrain));
    require_run_length(out.back(), model_entry(m).info().clock);
    check_model_preconditions(compute, out.back(), terrain);  // before the first model runs
  }
  return out;
}

}  // namespace

std::vector<ModelResult> run_compare(ComputeContext& compute, const Parameters& scenario,
                                     const Heightmap& terrain, const Options& options) {
  namespace fs = std::filesystem;
  RainBudget budget;
  const std::vector<Parameters> params =
      checked_parameters(compute, scenario, terrain, options, budget);
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec || !fs::is_directory(options.out_dir))
    throw input_error("--out " + options.out_dir + ": cannot create the output folder");

  std::vector<ModelResult> results;
  Heightmap initial;
  for (std::size_t k = 0; k < params.size(); ++k) {
    const std::string& name = options.models[k];
    if (!options.quiet)
      std::cerr << "compare: model " << k + 1 << "/" << params.size() << ": " << name << "\n";
    const std::unique_ptr<Model> model = make_model(compute, params[k], terrain);
    RunOptions run = run_options_from(params[k], model->info().clock);
    run.out_dir = (fs::path(options.out_dir) / name).string();
    run.quiet = options.quiet;
    const RunSummary s = run_model(compute, *model, run);
    ModelResult r;
    r.model = name;
    r.class_name = model->info().class_name;
    r.clock = clock_name(model->info().clock);
    r.folder = name;
    r.setup = setup_text(scenario, params[k]);
    r.caution = s.caution;
    r.steps = s.steps;
    r.time = s.sim_time;
    r.wall_seconds = s.wall_seconds;
    r.rain_volume = s.rain_volume;
    r.balance = s.balance;
    r.terrain_values = s.terrain_values;
    r.final_terrain = model->terrain();
    r.erosion_reference = model->erosion_reference();
    if (Ground* ground = model->ground()) {
      r.strata = ground->strata();
      const MaterialTally t = ground->tally();
      r.exposed = ground->exposed();
      const double vq = ground->quantum() * terrain.cell * terrain.cell;
      for (std::int64_t q : t.eroded) r.eroded_per_material.push_back(static_cast<double>(q) * vq);
    }
    if (model->info().clock == ModelClock::kSeconds) r.hydrograph = s.hydrograph;
    initial = model->initial_terrain();  // the same for every model: the input rounded to q
    results.push_back(std::move(r));
  }
  const fs::path out(options.out_dir);
  const std::string csv = metrics_csv(results);
  write_text_atomically((out / "metrics.csv").string(), csv);
  write_compare_png((out / "compare.png").string(), initial, results);
  std::string report = report_markdown(results, budget, initial, options);
  if (std::any_of(results.begin(), results.end(),
                  [](const ModelResult& r) { return !r.hydrograph.empty(); }))
    report +=
        "\nThe water leaving the terrain over its edges, each model with a clock in seconds, is in "
        "its MODEL/outflow.csv beside the rain and the water stored; `python -m runnel plot DIR` "
        "(or `runnel-plot DIR`) draws the hydrographs and the eroded and deposited volumes into "
        "DIR/figures/ as PNG and PDF.\n";
  write_text_atomically((out / "report.md").string(), report);
  return results;
}

namespace {

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::string metrics_csv(const std::vector<ModelResult>& results) {
  std::string out =
      "model,class,clock,steps,time,wall_seconds,rain_volume_m3,eroded_volume_m3,"
      "deposited_volume_m3,outflow_volume_m3,suspended_volume_m3,lost_volume_m3,"
      "mass_balance_abs_m3,mass_balance_rel";
  if (!results.empty()) {
    for (auto& [name, value] : results.front().terrain_values) out.append(",").append(name);
    if (results.front().strata)
      for (std::size_t m = 0; m < results.front().eroded_per_material.size(); ++m)
        out += ",eroded_" + results.front().strata->materials[m].name + "_m3";
  }
  out += "\n";
  for (const ModelResult& r : results) {
    const MassBalance& m = r.balance;
    out += r.model + "," + r.class_name + "," + r.clock + "," + std::to_string(r.steps) + "," +
           number(r.time) + "," + number(r.wall_seconds) + "," + number(r.rain_volume) + "," +
           number(m.eroded) + "," + number(m.deposited) + "," + number(m.outflow) + "," +
           number(m.suspended) + "," + number(m.lost) + "," + number(m.residual) + "," +
           number(m.relative);
    for (auto& [name, value] : r.terrain_values) out.append(",").append(number(value));
    for (double v : r.eroded_per_material) out.append(",").append(number(v));
    out += "\n";
  }
  return out;
}

}  // namespace runnel::compare
