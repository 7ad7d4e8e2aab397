// SPDX-License-Identifier: MIT
#include "runnel/core/scenario.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <variant>

#include "runnel/core/error.hpp"

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

std::string parameters_toml(const Parameters& params) {
  // Group keys by their table: "a.b" → [a] b, "terrain.set.x" → [terrain.set] x.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> tables;
  for (auto& [key, value] : params.values()) {
    const auto dot = key.rfind('.');
    std::string text = Parameters::to_text(value);
    if (std::holds_alternative<std::string>(value)) {
      std::string quoted = "\"";
      for (char c : text) {
        if (c == '"' || c == '\\') quoted += '\\';
        quoted += c;
      }
      text = quoted + "\"";
    } else if (std::holds_alternative<double>(value) &&
               text.find_first_of(".eEn") == std::string::npos) {
      text += ".0";  // keep reals real in TOML
    }
    tables[key.substr(0, dot)].emplace_back(key.substr(dot + 1), text);
  }
  for (auto& [key, value] : params.generator_values()) {
    std::ostringstream s;
    s.precision(17);
    s << value;
    tables["terrain.set"].emplace_back(key, s.str());
  }
  std::string out;
  for (auto& [table, entries] : tables) {
    out += "[" + table + "]\n";
    for (auto& [k, v] : entries) out += k + " = " + v + "\n";
  }
  return out;
}

}  // namespace runnel
