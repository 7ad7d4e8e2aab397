// SPDX-License-Identifier: MIT
// runnel generate: a seeded, deterministic terrain from one of the generators.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

#include "cli/commands.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/ground/ground_outputs.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/io/images.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_graph.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::cli {
namespace {

struct GenerateOptions {
  std::string name;
  std::string size = "257";
  double cell = 1.0;
  std::uint64_t seed = 1;
  std::vector<std::string> sets;
  std::string output;
  std::string range;
  std::string scenario;
  std::string picture;
  std::string graph;
  std::string device;
};

std::string generator_help() {
  std::ostringstream s;
  s << "\nGenerators and their --set parameters (default, unit):\n";
  for (auto& g : generators()) {
    s << "  " << g.name << ": " << g.description << "\n";
    for (auto& p : g.params) {
      s << "      " << p.key << " = " << p.default_value << " (" << p.unit << "; " << p.min_value
        << ".." << p.max_value << ")  " << p.help << "\n";
    }
  }
  return s.str();
}

void parse_size(const std::string& text, int& nx, int& ny) {
  const auto x = text.find('x');
  auto parse = [&](const std::string& s, int& v) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size())
      throw input_error("--size " + text + ": expected N or NXxNY");
  };
  parse(text.substr(0, x), nx);
  ny = nx;
  if (x != std::string::npos) parse(text.substr(x + 1), ny);
}

// The terrain the flags ask for: a graph, a scenario's terrain, or one generator; `params` gets the
// scenario's parameters (its layers among them).
Heightmap generated_terrain(const GenerateOptions& opt, const CLI::App& cmd, Parameters& params) {
  Heightmap terrain;
  if (!opt.graph.empty()) {
    if (!opt.name.empty() || !opt.scenario.empty())
      throw input_error(
          "--graph: the graph is the whole terrain; give no generator name or --scenario");
    // The noise generators on the device: the same bytes as on the host, faster.
    ComputeContext compute(opt.device);
    terrain = evaluate_terrain_graph(opt.graph, &compute);
  } else if (!opt.scenario.empty()) {
    params = load_scenario(opt.scenario);
    if (!opt.name.empty()) params.set("terrain.generator", opt.name, "generate");
    if (cmd.count("--size")) params.set_text("terrain.size", opt.size, "--size");
    if (cmd.count("--cell")) params.set("terrain.cell", opt.cell, "--cell");
    if (cmd.count("--seed"))
      params.set("terrain.seed", static_cast<std::int64_t>(opt.seed), "--seed");
    for (auto& s : opt.sets) apply_overrides(params, {"terrain.set." + s});
    terrain = load_terrain(params);
  } else {
    if (opt.name.empty()) throw input_error("generate: name a generator (or give --scenario)");
    int nx = 0, ny = 0;
    parse_size(opt.size, nx, ny);
    std::map<std::string, double> values;
    for (auto& s : opt.sets) {
      const auto eq = s.find('=');
      double v = 0;
      const std::string text = eq == std::string::npos ? "" : s.substr(eq + 1);
      const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (eq == std::string::npos || eq == 0 || ec != std::errc() ||
          p != text.data() + text.size()) {
        throw input_error("--set " + s + ": expected key=number");
      }
      values[s.substr(0, eq)] = v;
    }
    std::unique_ptr<ComputeContext> compute;
    if (find_generator(opt.name).on_device) compute = std::make_unique<ComputeContext>(opt.device);
    terrain = generate_terrain(opt.name, nx, ny, opt.cell, opt.seed, values, compute.get());
  }
  return terrain;
}

// Writes the terrain (and its picture, or a layered terrain's strata) after checking that no
// output replaces an input or another output.
void generate(const GenerateOptions& opt, const CLI::App& cmd) {
  Parameters params = default_parameters();
  const Heightmap terrain = generated_terrain(opt, cmd, params);
  std::vector<NamedPath> inputs = scenario_inputs(params, opt.scenario);
  inputs.push_back({"--graph", opt.graph});
  check_output_paths(inputs, {{"-o", opt.output}, {"--picture", opt.picture}});
  require_output_folders({{"-o", opt.output}, {"--picture", opt.picture}});
  if (!params.layers().empty()) {
    // The strata on the terrain as the run sees it: heights rounded to the quantum.
    const double q = params.real("erosion.height_quantum");
    std::vector<std::int64_t> fixed(terrain.size());
    for (std::size_t k = 0; k < fixed.size(); ++k) fixed[k] = std::llround(terrain.h[k] / q);
    for (const std::string& f :
         write_layered_terrain(opt.output, terrain, build_strata(params, terrain, fixed, q), q))
      std::fprintf(stderr, "runnel: wrote %s\n", terminal_safe(f).c_str());
    return;
  }
  if (std::filesystem::path(opt.output).extension() == ".h5")
    throw input_error("-o " + opt.output +
                      ": an .h5 output holds a layered terrain; give a "
                      "--scenario with [[layers]]");
  WriteOptions write;
  if (!opt.range.empty() && terrain_format_from_path(opt.output) != TerrainFormat::kPng)
    throw input_error("--range: only a PNG output has a height range");
  if (!opt.range.empty()) write.png_range = parse_range(opt.range, "--range");
  write_terrain(opt.output, terrain, write);
  if (!opt.picture.empty())
    write_png_rgb(opt.picture,
                  terrain_picture(terrain, terrain.min_height(), terrain.max_height()));
  std::fprintf(stderr, "runnel: wrote %s (%d x %d vertices, cell %g m, heights %.3f..%.3f m)\n",
               terminal_safe(opt.output).c_str(), terrain.nx, terrain.ny, terrain.cell,
               terrain.min_height(), terrain.max_height());
}

}  // namespace

void add_generate_command(CLI::App& app) {
  auto opt = std::make_shared<GenerateOptions>();
  auto* cmd =
      app.add_subcommand("generate",
                         "Generate a terrain (seeded, deterministic) and write it as .asc, .png, "
                         ".npy or .tif (format from the extension)");
  cmd->add_option("name", opt->name, "generator name (see below); omit with --scenario");
  cmd->add_option("--size", opt->size, "vertices per side N, or NXxNY")->capture_default_str();
  cmd->add_option("--cell", opt->cell, "cell size (vertex spacing) in metres")
      ->check(cell_size())
      ->capture_default_str();
  cmd->add_option("--seed", opt->seed, "random seed")
      ->check(whole_in(0, std::numeric_limits<std::int64_t>::max()))
      ->capture_default_str();
  cmd->add_option("--set", opt->sets, "generator parameter key=value (repeatable)");
  cmd->add_option("-o,--output", opt->output,
                  "output file (.asc, .png, .npy, .tif); with a layered --scenario also one "
                  "thickness raster per stratum (STEM.NAME.EXT), or .h5 for one HDF5 file with "
                  "the terrain and its layer stack")
      ->required();
  cmd->add_option("--range", opt->range,
                  "PNG only: heights MIN:MAX (m) mapped to 0..65535 (default: the terrain's)");
  cmd->add_option(
      "--picture", opt->picture,
      "also write a hillshaded picture of the terrain (coloured by height) to this PNG");
  cmd->add_option("--device", opt->device,
                  "OpenCL device of the noise generators (see 'runnel devices'); the bytes are the "
                  "same on every device and on the host");
  cmd->add_option("--graph", opt->graph,
                  "compose the terrain from a graph of generators, filters and input files "
                  "(TOML; docs/generators.md)");
  cmd->add_option("--scenario", opt->scenario,
                  "take the terrain (generator, size, cell, seed, [terrain.set]) from "
                  "a scenario file; flags given on the command line override it");
  cmd->footer(generator_help());
  cmd->callback([opt, cmd] { generate(*opt, *cmd); });
}

}  // namespace runnel::cli
