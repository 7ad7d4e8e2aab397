// SPDX-License-Identifier: MIT
// runnel resume: continues a run from an HDF5 checkpoint, exactly as if it had not stopped.
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameters_toml.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"

namespace runnel::cli {

namespace {

// The checkpoint's parameters with --set applied; the terrain (stored in the checkpoint) and the
// model (whose state it holds) cannot change.
std::string with_overrides(const std::string& stored, const std::vector<std::string>& sets) {
  for (const std::string& a : sets) {
    const std::string key = a.substr(0, a.find('='));
    if (key.rfind("terrain.", 0) == 0 || key == "run.model")
      throw input_error("--set " + runnel::quoted(key) +
                        ": a resumed run keeps the checkpoint's terrain and model");
  }
  Parameters params = default_parameters();
  read_parameters_toml(params, stored, "checkpoint parameters");
  apply_overrides(params, sets);
  return parameters_toml(params);
}

}  // namespace

void add_resume_command(CLI::App& app) {
  struct Options {
    std::string file, out = "runnel-out", device;
    long long steps = 0;
    bool quiet = false;
    std::vector<std::string> sets;
    OutputFlags output;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("resume",
                         "Continue a run from a checkpoint (.h5) for --steps more steps; the "
                         "result equals an uninterrupted run bit for bit");
  cmd->add_option("checkpoint", opt->file, "checkpoint file (final.h5 or checkpoints/step_*.h5)")
      ->required();
  cmd->add_option("--steps", opt->steps, "steps to add")->required()->check(whole_in(1, kMaxSteps));
  cmd->add_option("--out", opt->out, "output folder (created)")->capture_default_str();
  cmd->add_option("--device", opt->device,
                  "OpenCL device (see 'runnel devices'); the same device as the "
                  "original run for a bitwise-identical continuation");
  cmd->add_flag("--quiet", opt->quiet, "no progress output");
  cmd->add_option(
      "--set", opt->sets,
      "parameter key=value (repeatable) to go on with instead of the checkpoint's, e.g. "
      "a smaller sph.dt_max after a run stopped as unstable (failed.h5); the terrain and "
      "the model stay. With --set the continuation is no longer the uninterrupted run");
  add_output_flags(*cmd, opt->output);
  cmd->callback([opt] {
    check_run_outputs({{"checkpoint", opt->file}}, opt->out, "");
    CheckpointData data = read_checkpoint(opt->file);
    if (!opt->sets.empty()) data.parameters_toml = with_overrides(data.parameters_toml, opt->sets);
    ComputeContext compute(opt->device);
    const std::unique_ptr<Model> model = make_model_from_checkpoint(compute, data, opt->file);
    RunOptions options = run_options_from(model->parameters(), model->info().clock);
    options.until_step = model->steps() + static_cast<std::uint64_t>(opt->steps);
    options.out_dir = opt->out;
    options.resumed_counters = data.model_counters;
    options.quiet = opt->quiet;
    opt->output.apply(options);
    const RunSummary s = run_model(compute, *model, options);
    std::cout << terminal_safe(opt->out) << "/metrics.json: resumed at step " << data.steps
              << ", now " << s.steps << " steps, mass balance " << s.balance.residual << " m^3\n";
  });
}

}  // namespace runnel::cli
