// SPDX-License-Identifier: MIT
// The parameter table: every scenario key of runnel, with its default, unit, range and meaning.
// The drivers' own keys (terrain.*, run.*) are declared here; each settings group declares its keys
// once, beside the struct they fill (core/parameter_groups.hpp); each model's groups come from its
// registry entry, in the registry's order, and the ground's, which every model shares, after them.
#include "runnel/models/parameter_table.hpp"

#include "runnel/core/parameter_groups.hpp"
#include "runnel/models/registry.hpp"     // run.model's choices are the registry's names
#include "runnel/terrain/generators.hpp"  // terrain.generator's, the generators'

namespace runnel {
namespace {

std::vector<std::string> generator_names() {
  std::vector<std::string> names;
  for (const GeneratorSpec& g : generators()) names.push_back(g.name);
  return names;
}

}  // namespace
}  // namespace runnel

namespace runnel {

namespace {

std::vector<ParamSpec> assemble() {
  using T = ParamType;
  const std::vector<ParamSpec> terrain = {
      // clang-format off
      // terrain: where the heightmap comes from
      {"terrain.file", T::kString, "\"\"", "", 0, 0, {}, "terrain file (.asc, .png, .npy), relative to the scenario file; empty: use terrain.generator"},
      {"terrain.generator", T::kString, "\"fbm\"", "", 0, 0, generator_names(), "generator used when terrain.file and terrain.graph are empty; its own parameters go in [terrain.set] (docs/generators.md)"},
      {"terrain.graph", T::kString, "\"\"", "", 0, 0, {}, "a terrain graph (TOML: generators, filters, input files; docs/generators.md), relative to the scenario file; used when terrain.file is empty"},
      {"terrain.size", T::kInteger, "257", "vertices", 2, 32768, {}, "generated terrain: vertices per side"},
      {"terrain.cell", T::kReal, "1.0", "m", 1e-6, 1e6, {}, "cell size (vertex spacing); for files, the cell of a file that carries none (NPY, a foreign PNG), and of every file when terrain.cell_from_file is false"},
      {"terrain.cell_from_file", T::kBool, "true", "", 0, 0, {}, "take the cell size from the terrain file when it has one (ASC, runnel PNG)"},
      {"terrain.seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "generator seed"},
      {"terrain.nodata", T::kString, "\"fill\"", "", 0, 0, {"fill", "refuse"}, "NODATA cells in an ASCII grid: fill from neighbours, or refuse the file"},
      // clang-format on
  };
  const std::vector<ParamSpec> run = {
      // clang-format off
      // run: the simulation as a whole
      {"run.model", T::kString, "\"sph\"", "", 0, 0, model_names(), "erosion model (docs/models.md): sph (runnel's own), droplet (Beyer 2015), pipe (Mei 2007), olsen (Olsen 2004), thermal (talus), stream-power (Braun & Willett 2013, years)"},
      {"run.seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "seed of the simulation's random numbers (rain)"},
      {"run.steps", T::kInteger, "0", "steps", 0, 1e12, {}, "steps to run; 0: run for run.sim_time"},
      {"run.sim_time", T::kReal, "10", "s", 0, 1e12, {}, "simulated time to run when run.steps is 0 (models with a clock: sph and pipe in seconds, stream-power in years unless run.sim_years is set)"},
      {"run.sim_years", T::kReal, "0", "yr", 0, 1e12, {}, "simulated years to run when run.steps is 0, for models whose clock is years (stream-power), so one scenario can give seconds of rain and years of landscape evolution (runnel compare); 0: run.sim_time, read as years"},
      {"run.iterations", T::kInteger, "100", "iterations", 0, 1e12, {}, "iterations to run when run.steps is 0 (models counting iterations: droplet batches, olsen, thermal)"},
      {"run.probe_every", T::kReal, "0.1", "s", 1e-6, 1e12, {}, "clock time between the gauges' readings in probes.csv ([[probes]]; the model's clock: s for sph and pipe)"},
      {"run.outflow_every", T::kReal, "1", "s", 0, 1e12, {}, "clock time between the rows of outflow.csv, the water's budget (rain and outflow in m^3 per clock unit, the water on the terrain in m^3) for models with water (sph, pipe, olsen); 0: no outflow.csv"},
      {"run.outflow_edges", T::kBool, "false", "", 0, 0, {}, "outflow.csv also splits the outflow by edge (west, east, north, south; the grid models)"},
      {"run.report_every", T::kInteger, "200", "steps", 1, 1e12, {}, "steps between mass-balance reports (progress lines when not on a terminal)"},
      // clang-format on
  };
  std::vector<ParamSpec> table = terrain;
  for (const ModelEntry& model : model_registry())
    for (ParamSpec& spec : model.parameters()) table.push_back(std::move(spec));
  for (ParamSpec& spec : ground_parameters()) table.push_back(std::move(spec));  // every model's
  for (ParamSpec& spec : sediment_parameters()) table.push_back(std::move(spec));
  for (ParamSpec& spec : water_parameters()) table.push_back(std::move(spec));  // with water
  for (ParamSpec& spec : probe_parameters()) table.push_back(std::move(spec));
  table.insert(table.end(), run.begin(), run.end());
  return table;
}

}  // namespace

const ParameterTable& parameter_table() {
  static const ParameterTable table = assemble();
  return table;
}

Parameters default_parameters() {
  return Parameters(parameter_table());
}

const ParamSpec* find_param(const std::string& key) {
  return find_param(parameter_table(), key);
}

}  // namespace runnel
