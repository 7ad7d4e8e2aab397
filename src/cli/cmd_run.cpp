// SPDX-License-Identifier: MIT
// runnel run: rain on a terrain, SPH flow, erosion and deposition; pictures, terrain and metrics
// out.
#include <iostream>
#include <limits>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::cli {

namespace {

struct RunFlags {
  std::string scenario, terrain, generate, model, out = "runnel-out", device;
  long long steps = -1;
  double sim_time = -1;
  long long seed = -1;
  std::vector<std::string> sets;
  bool quiet = false;
  std::string trace;
  OutputFlags output;
};

// The scenario with the flags applied, checked, run and reported.
void run(const RunFlags& opt) {
  Parameters params = opt.scenario.empty() ? default_parameters() : load_scenario(opt.scenario);
  if (!opt.terrain.empty()) params.set("terrain.file", opt.terrain, "--terrain");
  if (!opt.generate.empty()) {
    params.set("terrain.file", std::string(), "--generate");
    params.set("terrain.generator", opt.generate, "--generate");
  }
  if (opt.steps >= 0) params.set("run.steps", static_cast<std::int64_t>(opt.steps), "--steps");
  if (opt.sim_time >= 0) {
    params.set("run.sim_time", opt.sim_time, "--sim-time");
    params.set("run.steps", static_cast<std::int64_t>(0), "--sim-time");
  }
  if (opt.seed >= 0) params.set("run.seed", static_cast<std::int64_t>(opt.seed), "--seed");
  apply_overrides(params, opt.sets);
  if (!opt.model.empty()) params.set("run.model", opt.model, "--model");
  const ModelClock clock = model_entry(params.text("run.model")).info().clock;
  if (opt.sim_time >= 0 && clock == ModelClock::kIterations) {
    throw input_error("--sim-time: the " + params.text("run.model") +
                      " model counts iterations, not seconds; use --steps or run.iterations");
  }
  if (opt.sim_time >= 0 && clock == ModelClock::kYears)  // the flag wins over the scenario
    params.set("run.sim_years", opt.sim_time, "--sim-time");
  require_run_length(params, clock);
  check_run_outputs(scenario_inputs(params, opt.scenario), opt.out, opt.trace);
  const Heightmap terrain = load_terrain(params);
  ComputeContext compute(opt.device);
  RunOptions options = run_options_from(params, clock);
  options.out_dir = opt.out;
  options.quiet = opt.quiet;
  opt.output.apply(options);
  // Building the model validates every setting before anything is written.
  const std::unique_ptr<Model> model = make_model(compute, params, terrain);
  if (!opt.trace.empty()) compute.profiler().trace_to(opt.trace);
  const RunSummary s = run_model(compute, *model, options);
  std::cout << terminal_safe(opt.out) << "/metrics.json: " << s.steps << " steps, mass balance "
            << s.balance.residual << " m^3 (relative " << s.balance.relative << ")\n";
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunFlags>();
  auto* cmd = app.add_subcommand(
      "run",
      "Run an erosion model on a terrain: by default runnel's SPH rain erosion (rain falls, flows, "
      "erodes and deposits), or droplet, pipe, olsen or thermal (--model). Writes "
      "height_initial.png, height_final.png, erosion.png, final.asc, final.npy, final.tif, "
      "erosion.tif (GeoTIFF, georeferenced like the input), final.h5, "
      "metrics.json and, with [[probes]] in the scenario, probes.csv into --out");
  cmd->add_option("scenario", opt->scenario,
                  "scenario file (TOML; see 'runnel params'); default: built-in defaults");
  auto* terrain = cmd->add_option("--terrain", opt->terrain,
                                  "terrain file (.asc, .png, .npy, .tif or another raster GDAL "
                                  "reads) instead of the scenario's");
  cmd->add_option("--generate", opt->generate, "generate the terrain with this generator instead")
      ->excludes(terrain);
  cmd->add_option(
         "--model", opt->model,
         "erosion model (run.model): sph, droplet, pipe, olsen, thermal or stream-power; see "
         "docs/models.md")
      ->check(CLI::IsMember(model_names()));
  auto* steps = cmd->add_option("--steps", opt->steps, "number of steps (run.steps)")
                    ->check(whole_in(1, kMaxSteps));
  cmd->add_option("--sim-time", opt->sim_time,
                  "simulated seconds (run.sim_time); years for a model whose clock is years "
                  "(stream-power: run.sim_years)")
      ->excludes(steps)
      ->check(at_least(1e-9));
  cmd->add_option("--seed", opt->seed, "random seed of the rain (run.seed)")
      ->check(whole_in(0, std::numeric_limits<std::int64_t>::max()));
  cmd->add_option("--out", opt->out, "output folder (created)")->capture_default_str();
  cmd->add_option("--set", opt->sets, "parameter key=value (repeatable; see 'runnel params')");
  cmd->add_option("--device", opt->device, "OpenCL device (see 'runnel devices')");
  cmd->add_flag("--quiet", opt->quiet, "no progress output");
  cmd->add_option("--trace", opt->trace,
                  "write every kernel launch to FILE as a Chrome trace (open it in Perfetto or "
                  "chrome://tracing; about 150 bytes a launch, ~35 launches an SPH step)")
      ->type_name("FILE");
  add_output_flags(*cmd, opt->output);
  cmd->callback([opt] { run(*opt); });
}

}  // namespace runnel::cli
