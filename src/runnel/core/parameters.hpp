// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <variant>
#include <vector>

namespace runnel {

// kEntries: a list of tables ([[key]] in TOML), each entry's keys declared by `entry_keys`.
enum class ParamType { kReal, kInteger, kBool, kString, kEntries };

// One simulation parameter, declared once: the scenario reader, `--set`, `runnel params`,
// docs/parameters.md and the outputs all iterate over this table (docs/architecture.md).
struct ParamSpec {
  std::string key;  // dotted TOML key, e.g. "terrain.cell"
  ParamType type;
  std::string default_value;  // as TOML-ish text: 1.5, 7, true, "fbm"
  std::string unit;           // SI unit, "1" for dimensionless, "" for text
  double min_value;           // valid range for numbers (inclusive)
  double max_value;
  std::vector<std::string> choices;  // allowed values for strings; empty = any
  std::string help;
  const std::vector<ParamSpec>* entry_keys = nullptr;  // kEntries: the keys of one entry

  // Whether a value of this parameter is written with a unit (text and dimensionless ones are not).
  bool has_unit() const { return !unit.empty() && unit != "1"; }
};

// A program's parameters, grouped by the key's first component. runnel's own table is assembled
// above the models (models/parameter_table.hpp); this layer works with any table.
using ParameterTable = std::vector<ParamSpec>;
const ParamSpec* find_param(const ParameterTable& table, const std::string& key);

using ParamValue = std::variant<double, std::int64_t, bool, std::string>;
// One entry of a list of tables: every key of its spec's entry_keys, given or at its default.
using EntryValues = std::map<std::string, ParamValue>;
// A number as a real (an integer read as one).
double real_value(const ParamValue& value);
// A number of an entry.
inline double entry_real(const EntryValues& entry, const std::string& key) {
  return real_value(entry.at(key));
}

// `value` checked against `spec` (an integer is accepted for a real): the type, the range, the
// choices. Throws an input error starting with `where`.
ParamValue validated_value(const ParamSpec& spec, const ParamValue& value,
                           const std::string& where);

// One stratum of a scenario's [[layers]]: the keys it sets, each validated against layer_table()
// (core/layers.cpp); the ground builds the stratum from them (ground/strata.cpp).
using LayerValues = EntryValues;

// A validated set of parameter values: every key of the table has a value (its default unless set).
class Parameters {
 public:
  explicit Parameters(const ParameterTable& table);  // all defaults; the table outlives the set

  const ParameterTable& table() const { return *table_; }

  // Sets from text (`--set key=value`, TOML values). Throws an input error naming `origin` and the
  // key.
  void set_text(const std::string& key, const std::string& text,
                const std::string& origin = "--set");
  void set(const std::string& key, const ParamValue& value, const std::string& origin = "--set");

  // Whether the key was set explicitly (scenario, --set), rather than holding its default.
  bool was_set(const std::string& key) const { return explicit_.count(key) > 0; }

  double real(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& text(const std::string& key) const;

  // Generator parameters ("terrain.set.KEY"); validated against the generator when it runs.
  std::map<std::string, double>& generator_values() { return generator_values_; }
  const std::map<std::string, double>& generator_values() const { return generator_values_; }

  // The strata, top first ([[layers]] in the scenario). Checked when added: known keys, valid
  // values, a unique name and one way of giving the thickness.
  void add_layer(const LayerValues& layer, const std::string& origin);
  const std::vector<LayerValues>& layers() const { return layers_; }

  // A list of tables (a kEntries key): each entry checked against the spec's entry_keys (unknown
  // keys, types, ranges), its other keys at their defaults. Throws an input error naming `origin`,
  // the list, the entry's number and the key.
  void add_entry(const std::string& key, const EntryValues& given, const std::string& origin);
  // The entries of a kEntries key, in the order given (empty unless set).
  const std::vector<EntryValues>& entries(const std::string& key) const;
  const std::map<std::string, std::vector<EntryValues>>& all_entries() const { return entries_; }
  // Replaces one key of layer `index` (already validated; the scenario reader resolves paths).
  void set_layer_value(std::size_t index, const std::string& key, const ParamValue& value) {
    layers_.at(index)[key] = value;
  }

  const std::map<std::string, ParamValue>& values() const { return values_; }
  static std::string to_text(const ParamValue& value);

 private:
  const ParamValue& get(const std::string& key) const;
  const ParameterTable* table_;
  std::map<std::string, ParamValue> values_;
  std::map<std::string, double> generator_values_;
  std::vector<LayerValues> layers_;
  std::map<std::string, std::vector<EntryValues>> entries_;
  std::set<std::string> explicit_;
};

// docs/parameters.md, generated from the table (`runnel params --markdown`).
std::string parameters_markdown(const ParameterTable& table);

}  // namespace runnel
