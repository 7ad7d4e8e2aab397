// SPDX-License-Identifier: MIT
#include "runnel/core/parameters_toml.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <variant>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"
#include "runnel/core/layers.hpp"
#include "runnel/core/text.hpp"

namespace runnel {
namespace {

// A TOML value as a parameter value; `where` names it in the error.
ParamValue toml_value(const toml::node& node, const std::string& where) {
  if (node.is_integer()) return static_cast<std::int64_t>(node.as_integer()->get());
  if (node.is_floating_point()) return node.as_floating_point()->get();
  if (node.is_boolean()) return node.as_boolean()->get();
  if (node.is_string()) return node.as_string()->get();
  throw input_error(where + ": unsupported value (arrays and dates are not parameters)");
}

// [[layers]]: an array of tables, one stratum each, top first.
void read_layers(const toml::node& node, Parameters& params, const std::string& origin) {
  const toml::array* layers = node.as_array();
  if (!layers || !layers->is_array_of_tables())
    throw input_error(origin + " layers: expected [[layers]] tables, one per stratum");
  for (const toml::node& entry : *layers) {
    LayerValues layer;
    const std::string where =
        origin + " layers[" + std::to_string(params.layers().size() + 1) + "]";
    for (auto&& [k, value] : *entry.as_table())
      layer[std::string(k.str())] = toml_value(value, where + "." + std::string(k.str()));
    params.add_layer(layer, origin);
  }
}

// [[key]]: a list of tables, each an entry of a kEntries parameter.
void read_entries(const toml::node& node, const std::string& key, Parameters& params,
                  const std::string& origin) {
  const toml::array* list = node.as_array();
  if (!list || !list->is_array_of_tables())
    throw input_error(origin + " " + key + ": expected [[" + key + "]] tables, one per entry");
  for (const toml::node& table : *list) {
    EntryValues entry;
    const std::string where =
        origin + " " + key + "[" + std::to_string(params.entries(key).size() + 1) + "]";
    for (auto&& [k, value] : *table.as_table())
      entry[std::string(k.str())] = toml_value(value, where + "." + std::string(k.str()));
    params.add_entry(key, entry, origin);
  }
}

void flatten(const toml::table& table, const std::string& prefix, Parameters& params,
             const std::string& origin) {
  for (auto&& [k, node] : table) {
    const std::string key =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (key == "layers") continue;  // read after every flat key (ground.bedrock_name)
    if (auto* sub = node.as_table()) {
      const bool known_group =
          key == "terrain.set" ||
          std::any_of(params.table().begin(), params.table().end(),
                      [&](const ParamSpec& p) { return p.key.rfind(key + ".", 0) == 0; });
      if (!known_group) throw input_error(origin + ": unknown table [" + key + "]");
      flatten(*sub, key, params, origin);
      continue;
    }
    const ParamSpec* spec = find_param(params.table(), key);
    if (spec && spec->type == ParamType::kEntries) {
      read_entries(node, key, params, origin);
      continue;
    }
    params.set(key, toml_value(node, origin + " " + key), origin);
  }
}

// A value as TOML text that reads back to the same value.
std::string toml_text(const ParamValue& value) {
  std::string text = Parameters::to_text(value);
  if (std::holds_alternative<std::string>(value)) {
    std::string quoted = "\"";
    for (char c : text) {
      if (c == '"' || c == '\\') quoted += '\\';
      quoted += c;
    }
    return quoted + "\"";
  }
  if (std::holds_alternative<double>(value) && text.find_first_of(".eEn") == std::string::npos)
    text += ".0";  // keep reals real in TOML
  return text;
}

}  // namespace

void read_parameters_toml(Parameters& params, const std::string& text, const std::string& origin) {
  check_toml_key_depth(text, origin);
  toml::table table;
  try {
    table = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw input_error(origin + ":" + std::to_string(where.line) + ":" +
                      std::to_string(where.column) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  flatten(table, "", params, origin);
  if (const toml::node* layers = table.get("layers")) read_layers(*layers, params, origin);
}

void apply_overrides(Parameters& params, const std::vector<std::string>& assignments) {
  for (auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw input_error("--set " + a + ": expected key=value");
    params.set_text(a.substr(0, eq), a.substr(eq + 1));
  }
}

void require_override_groups(const std::vector<std::string>& assignments,
                             const std::vector<std::string>& groups, const std::string& what) {
  for (const std::string& a : assignments) {
    const std::string key = a.substr(0, a.find('='));
    const std::string group = key.substr(0, key.find('.'));
    if (std::find(groups.begin(), groups.end(), group) != groups.end()) continue;
    std::string read;
    for (const std::string& g : groups) read += (read.empty() ? "" : ", ") + g + ".*";
    throw input_error("--set " + quoted(key) + ": " + what + " does not read it (only " + read +
                      ")");
  }
}

std::string parameters_toml(const Parameters& params) {
  // Group keys by their table: "a.b" → [a] b, "terrain.set.x" → [terrain.set] x.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> tables;
  for (auto& [key, value] : params.values()) {
    const auto dot = key.rfind('.');
    tables[key.substr(0, dot)].emplace_back(key.substr(dot + 1), toml_text(value));
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
  for (const auto& [key, list] : params.all_entries())
    for (const EntryValues& entry : list) {
      out += "[[" + key + "]]\n";
      for (auto& [k, v] : entry) out += k + " = " + toml_text(v) + "\n";
    }
  for (const LayerValues& layer : params.layers()) {
    out += "[[layers]]\n";
    for (auto& [k, v] : layer) out += k + " = " + toml_text(v) + "\n";
  }
  return out;
}

}  // namespace runnel
