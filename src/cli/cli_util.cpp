// SPDX-License-Identifier: MIT
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/sim/output_folder.hpp"
#include "runnel/sim/scenario.hpp"

namespace runnel::cli {

CLI::Validator at_least(double min) {
  char rule[64];
  std::snprintf(rule, sizeof rule, "must be at least %g", min);
  return CLI::Validator(
      [min, rule = std::string(rule)](std::string& text) -> std::string {
        double v = 0;
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size() || !std::isfinite(v) || v < min)
          return rule + " (got " + text + ")";
        return "";
      },
      "");
}

CLI::Validator whole_in(long long min, long long max) {
  const std::string rule =
      "must be a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, rule](std::string& text) -> std::string {
        long long v = 0;
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size() || v < min || v > max)
          return rule + " (got " + text + ")";
        return "";
      },
      "");
}

CLI::Validator cell_size() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size() || !(v >= 1e-6 && v <= 1e6))
          return "a cell size must be 1e-6 to 1e6 m (got " + text + ")";
        return "";
      },
      "");
}

void add_output_flags(CLI::App& cmd, OutputFlags& flags) {
  cmd.add_option(
         "--checkpoint-every", flags.checkpoint_every,
         "write DIR/checkpoints/step_XXXXXXXX.h5 every N steps; 0 (the default): none (final.h5 "
         "is always written)")
      ->check(whole_in(0, kMaxSteps));
  cmd.add_option("--keep-checkpoints", flags.keep_checkpoints, "keep the newest K checkpoints")
      ->check(whole_in(1, 1000000))
      ->capture_default_str();
  cmd.add_option(
         "--series-every", flags.series_every,
         "append the heightmap to DIR/series.h5 every N steps (series.xmf indexes it for "
         "ParaView and VisIt; series.pvd with series_vtk/ holds the same frames as VTK files, "
         "terrain and particles as named blocks); 0 (the default): no series")
      ->check(whole_in(0, kMaxSteps));
  cmd.add_option(
         "--particles-every", flags.particles_every,
         "SPH: snapshot the particles (position, velocity, density, sediment, age, id) into "
         "DIR/series.h5 every N steps; 0 (the default): none")
      ->check(whole_in(0, kMaxSteps));
  cmd.add_flag("--overwrite", flags.overwrite,
               "replace the outputs of another run found in DIR (pictures, terrains, series, "
               "checkpoints; refused otherwise); files runnel did not write are kept");
}

void OutputFlags::apply(RunOptions& options) const {
  options.checkpoint_every = checkpoint_every;
  options.keep_checkpoints = keep_checkpoints;
  options.series_every = series_every;
  options.particles_every = particles_every;
  options.overwrite = overwrite;
}

std::vector<NamedPath> scenario_inputs(const Parameters& params, const std::string& scenario) {
  std::vector<NamedPath> inputs;
  if (!scenario.empty()) inputs.push_back({"scenario file", scenario});
  for (auto& [key, path] : input_files(params)) inputs.push_back({key, path});
  return inputs;
}

void check_run_outputs(const std::vector<NamedPath>& inputs, const std::string& out,
                       const std::string& trace) {
  std::vector<NamedPath> outputs;
  if (!trace.empty()) outputs.push_back({"--trace", trace});
  for (const std::string& name : run_output_names())
    outputs.push_back({"--out", (std::filesystem::path(out) / name).string()});
  check_output_paths(inputs, outputs);
}

HeightRange parse_range(const std::string& text, const std::string& flag) {
  // The separator is the first ':' after the first character, so "-10:20" parses as [-10, 20].
  const auto colon = text.find(':', 1);
  HeightRange r;
  auto parse = [](const std::string& s, double& v) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && p == s.data() + s.size() && std::isfinite(v);
  };
  if (colon == std::string::npos || !parse(text.substr(0, colon), r.min) ||
      !parse(text.substr(colon + 1), r.max)) {
    throw input_error(flag + " " + text + ": expected MIN:MAX in metres");
  }
  if (!(r.max > r.min)) throw input_error(flag + " " + text + ": MAX must be greater than MIN");
  return r;
}

void refuse_unclear_values(CLI::App& app) {
  const CLI::Validator not_empty(
      [](std::string& value) { return value.empty() ? std::string("empty value") : std::string(); },
      "TEXT", "not empty");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_max() == 0) {
      option->disable_flag_override();
    } else {
      option->check(not_empty);
    }
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    refuse_unclear_values(*sub);
}

}  // namespace runnel::cli
