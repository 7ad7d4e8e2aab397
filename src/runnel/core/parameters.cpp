// SPDX-License-Identifier: MIT
#include "runnel/core/parameters.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/layers.hpp"

namespace runnel {
namespace {

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::kReal:
      return "a number";
    case ParamType::kInteger:
      return "an integer";
    case ParamType::kBool:
      return "true or false";
    case ParamType::kString:
      return "a string";
    case ParamType::kEntries:
      return "a list of tables";
  }
  return "";
}

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

ParamValue parse_text(const ParamSpec& spec, std::string text, const std::string& where) {
  auto fail = [&]() -> ParamValue {
    throw input_error(where + ": expected " + type_name(spec.type) + ", got '" + text + "'");
  };
  switch (spec.type) {
    case ParamType::kReal: {
      double v = 0;
      const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || p != text.data() + text.size()) return fail();
      return v;
    }
    case ParamType::kInteger: {
      std::int64_t v = 0;
      const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || p != text.data() + text.size()) return fail();
      return v;
    }
    case ParamType::kBool:
      if (text == "true" || text == "1") return true;
      if (text == "false" || text == "0") return false;
      return fail();
    case ParamType::kString:
      if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
        text = text.substr(1, text.size() - 2);
      return text;
    case ParamType::kEntries:
      throw input_error(where + ": a list of tables; give each entry as [[" + spec.key +
                        "]] in a scenario file");
  }
  return fail();
}

}  // namespace

ParamValue validated_value(const ParamSpec& spec_ref, const ParamValue& value_in,
                           const std::string& where) {
  const ParamSpec* spec = &spec_ref;
  if (spec->type == ParamType::kEntries)
    throw input_error(where + ": a list of tables; give each entry as [[" + spec->key +
                      "]] in a scenario file");
  auto to_text = [](const ParamValue& v) { return Parameters::to_text(v); };
  ParamValue value = value_in;
  // An integer is a fine value for a real parameter.
  if (spec->type == ParamType::kReal) {
    if (auto* i = std::get_if<std::int64_t>(&value)) value = static_cast<double>(*i);
  }
  const bool type_ok =
      (spec->type == ParamType::kReal && std::holds_alternative<double>(value)) ||
      (spec->type == ParamType::kInteger && std::holds_alternative<std::int64_t>(value)) ||
      (spec->type == ParamType::kBool && std::holds_alternative<bool>(value)) ||
      (spec->type == ParamType::kString && std::holds_alternative<std::string>(value));
  if (!type_ok)
    throw input_error(where + ": expected " + type_name(spec->type) + ", got '" + to_text(value) +
                      "'");
  if (spec->type == ParamType::kReal || spec->type == ParamType::kInteger) {
    const double v = spec->type == ParamType::kReal
                         ? std::get<double>(value)
                         : static_cast<double>(std::get<std::int64_t>(value));
    if (!std::isfinite(v) || v < spec->min_value || v > spec->max_value) {
      throw input_error(where + ": " + to_text(value) + " is outside the valid range [" +
                        format_number(spec->min_value) + ", " + format_number(spec->max_value) +
                        "]" + (spec->has_unit() ? " " + spec->unit : ""));
    }
  }
  if (spec->type == ParamType::kString && !spec->choices.empty()) {
    const auto& s = std::get<std::string>(value);
    if (std::find(spec->choices.begin(), spec->choices.end(), s) == spec->choices.end()) {
      std::string list;
      for (auto& c : spec->choices) list += (list.empty() ? "" : ", ") + c;
      throw input_error(where + ": '" + s + "' is not one of " + list);
    }
  }
  return value;
}

double real_value(const ParamValue& v) {
  if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::get<double>(v);
}

const ParamSpec* find_param(const ParameterTable& table, const std::string& key) {
  for (auto& p : table) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

Parameters::Parameters(const ParameterTable& table) : table_(&table) {
  for (auto& spec : table)
    if (spec.type != ParamType::kEntries)
      values_[spec.key] = parse_text(spec, spec.default_value, spec.key);
}

void Parameters::set_text(const std::string& key, const std::string& text,
                          const std::string& origin) {
  const std::string where = origin + " " + key;
  if (key.rfind("terrain.set.", 0) == 0) {
    double v = 0;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || p != text.data() + text.size()) {
      throw input_error(where + ": expected a number, got '" + text + "'");
    }
    generator_values_[key.substr(12)] = v;
    return;
  }
  const ParamSpec* spec = find_param(*table_, key);
  if (!spec) throw input_error(where + ": unknown parameter (see 'runnel params')");
  set(key, parse_text(*spec, text, where), origin);
}

void Parameters::set(const std::string& key, const ParamValue& value_in,
                     const std::string& origin) {
  const std::string where = origin + " " + key;
  if (key.rfind("terrain.set.", 0) == 0) {
    if (auto* d = std::get_if<double>(&value_in))
      generator_values_[key.substr(12)] = *d;
    else if (auto* i = std::get_if<std::int64_t>(&value_in))
      generator_values_[key.substr(12)] = static_cast<double>(*i);
    else
      throw input_error(where + ": expected a number");
    return;
  }
  const ParamSpec* spec = find_param(*table_, key);
  if (!spec) throw input_error(where + ": unknown parameter (see 'runnel params')");
  const ParamValue value = validated_value(*spec, value_in, where);
  values_[key] = value;
  explicit_.insert(key);
}

void Parameters::add_entry(const std::string& key, const EntryValues& given,
                           const std::string& origin) {
  const ParamSpec* spec = find_param(*table_, key);
  if (!spec || spec->type != ParamType::kEntries)
    throw input_error(origin + " " + key + ": unknown list of tables (see 'runnel params')");
  std::vector<EntryValues>& list = entries_[key];
  const std::string where = origin + " " + key + "[" + std::to_string(list.size() + 1) + "]";
  EntryValues entry;
  for (const ParamSpec& sub : *spec->entry_keys)
    entry[sub.key] = parse_text(sub, sub.default_value, where + "." + sub.key);
  for (const auto& [sub_key, value] : given) {
    const ParamSpec* sub = find_param(*spec->entry_keys, sub_key);
    if (!sub) throw input_error(where + "." + sub_key + ": unknown key (see 'runnel params')");
    entry[sub_key] = validated_value(*sub, value, where + "." + sub_key);
  }
  list.push_back(std::move(entry));
  explicit_.insert(key);
}

const std::vector<EntryValues>& Parameters::entries(const std::string& key) const {
  static const std::vector<EntryValues> none;
  const ParamSpec* spec = find_param(*table_, key);
  if (!spec || spec->type != ParamType::kEntries)
    throw runtime_error("internal: '" + key + "' is not a declared list of tables");
  auto it = entries_.find(key);
  return it == entries_.end() ? none : it->second;
}

const ParamValue& Parameters::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw runtime_error("internal: parameter '" + key + "' is not declared");
  return it->second;
}

double Parameters::real(const std::string& key) const {
  return std::get<double>(get(key));
}
std::int64_t Parameters::integer(const std::string& key) const {
  return std::get<std::int64_t>(get(key));
}
bool Parameters::boolean(const std::string& key) const {
  return std::get<bool>(get(key));
}
const std::string& Parameters::text(const std::string& key) const {
  return std::get<std::string>(get(key));
}

std::string Parameters::to_text(const ParamValue& value) {
  if (auto* d = std::get_if<double>(&value)) {
    std::ostringstream s;
    s.precision(17);
    s << *d;
    return s.str();
  }
  if (auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return std::get<std::string>(value);
}

namespace {

// One row of docs/parameters.md's tables.
std::string markdown_row(const ParamSpec& p, const std::string& shown_key) {
  std::string range;
  if (p.type == ParamType::kReal || p.type == ParamType::kInteger) {
    range = format_number(p.min_value) + " .. " + format_number(p.max_value);
  } else if (!p.choices.empty()) {
    for (auto& c : p.choices) range += (range.empty() ? "" : ", ") + c;
  }
  const char* type = p.type == ParamType::kReal      ? "real"
                     : p.type == ParamType::kInteger ? "integer"
                     : p.type == ParamType::kBool    ? "bool"
                     : p.type == ParamType::kEntries ? "tables"
                                                     : "string";
  return "| `" + shown_key + "` | " + type + " | `" + p.default_value + "` | " + p.unit + " | " +
         range + " | " + p.help + " |\n";
}

}  // namespace

std::string parameters_markdown(const ParameterTable& table) {
  std::ostringstream out;
  out << "# Parameters\n\n"
      << "Generated by `runnel params --markdown` from the parameter table "
         "(src/runnel/models/parameter_table.cpp);\n"
      << "a test fails when this file and the table disagree. Set them in a scenario file (TOML, "
         "one table per\n"
      << "group: `[terrain]`, ...) or on the command line with `--set key=value`.\n"
      << "Generator parameters go in `[terrain.set]` (see `runnel generate --help`).\n";
  std::string group;
  for (auto& p : table) {
    const std::string g = p.key.substr(0, p.key.find('.'));
    if (g != group) {
      group = g;
      out << "\n## [" << group
          << "]\n\n| key | type | default | unit | range | meaning |\n|---|---|---|---|---|---|\n";
    }
    out << markdown_row(p, p.key);
    if (p.type == ParamType::kEntries)
      for (const ParamSpec& sub : *p.entry_keys) out << markdown_row(sub, p.key + "[]." + sub.key);
  }
  out << layers_markdown();
  return out.str();
}

}  // namespace runnel
