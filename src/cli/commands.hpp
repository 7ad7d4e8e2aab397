// SPDX-License-Identifier: MIT
// Each subcommand lives in its own file and registers itself on the root app.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "runnel/core/parameters.hpp"
#include "runnel/io/output_paths.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel::cli {

void add_devices_command(CLI::App& app);
void add_generate_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_params_command(CLI::App& app);
void add_validate_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_resume_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_compare_command(CLI::App& app);
// On every option of `app` and its subcommands: a value given empty (`--terrain ''`) is refused,
// and a flag takes no value (`--overwrite=2` is refused, not read as true).
void refuse_unclear_values(CLI::App& app);

// Flags shared by `run` and `resume`: checkpoints and the heightmap series.
struct OutputFlags {
  long long checkpoint_every = 0;
  int keep_checkpoints = 3;
  long long series_every = 0;
  long long particles_every = 0;
  bool overwrite = false;
  void apply(RunOptions& options) const;
};
void add_output_flags(CLI::App& cmd, OutputFlags& flags);

// A flag's number must be finite and at least `min` (integers: whole too). The message is one line
// that states the rule and echoes the value: "--steps: must be at least 1 (got -3)". (CLI11's own
// range checks print "not in range 0.000000 to 1797…".)
CLI::Validator at_least(double min);
// A whole number of steps, a seed, a count: within [min, max], refused beyond (CLI11 would clamp
// 1e30 to the largest 64-bit integer and run forever).
CLI::Validator whole_in(long long min, long long max);
inline constexpr long long kMaxSteps = 1000000000000LL;  // run.steps' own bound
// A cell size in metres: finite, within 1e-6 .. 1e6 m (terrain.cell's range).
CLI::Validator cell_size();

// The files the parameters name (terrain, graph, masks, uplift, layer thicknesses) and the
// scenario file itself, as inputs no output may replace.
std::vector<NamedPath> scenario_inputs(const Parameters& params, const std::string& scenario = "");

// Refuses, before anything runs, a run whose outputs (every file runnel writes into `out`, and
// `trace`) would replace one of `inputs` or one another, or a device, FIFO or folder.
void check_run_outputs(const std::vector<NamedPath>& inputs, const std::string& out,
                       const std::string& trace);

// "MIN:MAX" → a height range; throws an input error naming `flag`.
HeightRange parse_range(const std::string& text, const std::string& flag);

}  // namespace runnel::cli
