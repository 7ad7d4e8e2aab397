// SPDX-License-Identifier: MIT
#include "runnel/sim/scenario.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

void flatten(const toml::table& table, const std::string& prefix, Parameters& params,
             const std::string& origin) {
  for (auto&& [k, node] : table) {
    const std::string key =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto* sub = node.as_table()) {
      const bool known_group =
          key == "terrain.set" ||
          std::any_of(parameter_table().begin(), parameter_table().end(),
                      [&](const ParamSpec& p) { return p.key.rfind(key + ".", 0) == 0; });
      if (!known_group) throw input_error(origin + ": unknown table [" + key + "]");
      flatten(*sub, key, params, origin);
      continue;
    }
    if (node.is_integer())
      params.set(key, static_cast<std::int64_t>(node.as_integer()->get()), origin);
    else if (node.is_floating_point())
      params.set(key, node.as_floating_point()->get(), origin);
    else if (node.is_boolean())
      params.set(key, node.as_boolean()->get(), origin);
    else if (node.is_string())
      params.set(key, node.as_string()->get(), origin);
    else
      throw input_error(origin + " " + key +
                        ": unsupported value (arrays and dates are not parameters)");
  }
}

}  // namespace

Parameters parse_scenario(const std::string& text, const std::string& origin,
                          const std::string& base_dir) {
  toml::table table;
  try {
    table = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw input_error(origin + ":" + std::to_string(where.line) + ":" +
                      std::to_string(where.column) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  Parameters params;
  flatten(table, "", params, origin);
  const std::string& file = params.text("terrain.file");
  if (!file.empty() && !base_dir.empty() && std::filesystem::path(file).is_relative()) {
    params.set("terrain.file", (std::filesystem::path(base_dir) / file).lexically_normal().string(),
               origin);
  }
  return params;
}

Parameters load_scenario(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw input_error(path + ": no such scenario file");
  std::ifstream in(path);
  if (!in) throw input_error(path + ": cannot open for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scenario(buffer.str(), path, std::filesystem::path(path).parent_path().string());
}

void apply_overrides(Parameters& params, const std::vector<std::string>& assignments) {
  for (auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw input_error("--set " + a + ": expected key=value");
    params.set_text(a.substr(0, eq), a.substr(eq + 1));
  }
}

Heightmap load_terrain(const Parameters& params) {
  const std::string& file = params.text("terrain.file");
  if (!file.empty()) {
    ReadOptions options;
    options.nodata =
        params.text("terrain.nodata") == "refuse" ? NodataPolicy::kRefuse : NodataPolicy::kFill;
    if (!params.boolean("terrain.cell_from_file")) options.cell = params.real("terrain.cell");
    Heightmap terrain = read_terrain(file, options);
    return terrain;
  }
  const int size = static_cast<int>(params.integer("terrain.size"));
  try {
    return generate_terrain(
        params.text("terrain.generator"), size, size, params.real("terrain.cell"),
        static_cast<std::uint64_t>(params.integer("terrain.seed")), params.generator_values());
  } catch (const Error& e) {
    // Name the scenario key rather than the CLI flag the generator speaks of.
    std::string msg = e.what();
    if (msg.rfind("--set ", 0) == 0) msg = "terrain.set." + msg.substr(6);
    throw Error(e.code(), msg);
  }
}

}  // namespace runnel
