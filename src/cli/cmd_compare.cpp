// SPDX-License-Identifier: MIT
// runnel compare: several erosion models on one terrain with one rain budget, side by side.
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/compare/compare.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::cli {
namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

}  // namespace

void add_compare_command(CLI::App& app) {
  struct Options {
    std::string scenario, terrain, models, out = "runnel-compare", device;
    std::vector<std::string> sets;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  std::string all;
  for (const std::string& name : model_names()) all += (all.empty() ? "" : ",") + name;
  opt->models = all;
  auto* cmd = app.add_subcommand(
      "compare",
      "Run several erosion models on the same terrain with the same rain budget and compare them: "
      "writes OUT/MODEL/ (as 'runnel run'), OUT/metrics.csv (a row per model), OUT/compare.png "
      "(initial terrain, each model's final terrain and erosion map, one colour scale) and "
      "OUT/report.md. The budget is the SPH scenario's rain over run.sim_time (docs/models.md)");
  cmd->add_option("scenario", opt->scenario,
                  "scenario file (TOML; see 'runnel params'); default: built-in defaults");
  cmd->add_option("--models", opt->models, "comma-separated models to run, in order")
      ->capture_default_str();
  cmd->add_option("--terrain", opt->terrain,
                  "terrain file (.asc, .png, .npy, .tif or another raster GDAL reads) instead of "
                  "the scenario's");
  cmd->add_option("--out", opt->out, "output folder (created)")->capture_default_str();
  cmd->add_option("--set", opt->sets, "parameter key=value (repeatable; see 'runnel params')");
  cmd->add_option("--device", opt->device, "OpenCL device (see 'runnel devices')");
  cmd->add_flag("--quiet", opt->quiet, "no progress output");
  cmd->callback([opt] {
    Parameters params = opt->scenario.empty() ? default_parameters() : load_scenario(opt->scenario);
    if (!opt->terrain.empty()) params.set("terrain.file", opt->terrain, "--terrain");
    apply_overrides(params, opt->sets);
    compare::Options options;
    options.models = split_list(opt->models);  // names checked by run_compare
    options.out_dir = opt->out;
    options.quiet = opt->quiet;
    options.scenario_name = opt->scenario.empty() ? "built-in defaults" : opt->scenario;
    const std::vector<NamedPath> inputs = scenario_inputs(params, opt->scenario);
    for (const std::string& model : options.models)
      check_run_outputs(inputs, (std::filesystem::path(opt->out) / model).string(), "");
    check_output_paths(inputs, {{"--out", opt->out + "/metrics.csv"},
                                {"--out", opt->out + "/compare.png"},
                                {"--out", opt->out + "/report.md"}});
    const Heightmap terrain = load_terrain(params);
    ComputeContext compute(opt->device);
    const auto results = compare::run_compare(compute, params, terrain, options);
    std::cout << terminal_safe(opt->out) << "/report.md: " << results.size()
              << " models; metrics.csv, compare.png\n";
    for (const auto& r : results) {
      std::cout << "  " << r.model << ": eroded " << r.balance.eroded << " m^3, mass balance "
                << r.balance.residual << " m^3\n";
    }
  });
}

}  // namespace runnel::cli
