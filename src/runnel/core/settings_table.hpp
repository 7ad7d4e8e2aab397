// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "runnel/core/error.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/core/text.hpp"

namespace runnel {

// One parameter of a settings group, declared once: its scenario key, type, default, unit, range
// and help (the ParamSpec that `runnel params`, docs/parameters.md and the scenario reader see),
// the struct member it fills and, where a kernel reads it as it is, the -D define it becomes. A
// group's `from()` reads every row with read_settings(), its `build_options()` starts from
// settings_defines(), and runnel's parameter table (models/parameter_table.hpp) is the
// concatenation of the groups' specs, so a key, its default and its destination can no longer drift
// apart. A parameter the group resolves into something else (0 = automatic, a multiple of dx) still
// fills its member here; from() then resolves it in place and says why.
template <class S>
struct Setting {
  using Member =
      std::variant<double S::*, std::int64_t S::*, int S::*, bool S::*, std::string S::*>;
  // As in ParamSpec, less the type: that comes from the member.
  std::string key;
  std::string default_value;
  std::string unit;
  double min_value;
  double max_value;
  std::vector<std::string> choices;
  std::string help;
  Member member;
  const char* define = nullptr;  // kernel define for the raw value; nullptr: none
};

template <class S>
using SettingsTable = std::vector<Setting<S>>;

// Every row's value from the parameters into a fresh S.
template <class S>
S read_settings(const Parameters& p, const SettingsTable<S>& table) {
  S s{};
  for (const Setting<S>& row : table) {
    const std::string& key = row.key;
    std::visit(
        [&](auto member) {
          using V = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<V, double>) {
            s.*member = p.real(key);
          } else if constexpr (std::is_same_v<V, std::int64_t>) {
            s.*member = p.integer(key);
          } else if constexpr (std::is_same_v<V, int>) {
            s.*member = static_cast<int>(p.integer(key));
          } else if constexpr (std::is_same_v<V, bool>) {
            s.*member = p.boolean(key);
          } else {
            s.*member = p.text(key);
          }
        },
        row.member);
  }
  return s;
}

// " -DNAME=value" for every row with a define: reals as exact floats (float_define), integers
// and booleans as integers.
template <class S>
std::string settings_defines(const S& s, const SettingsTable<S>& table) {
  std::string o;
  char buf[160];
  for (const Setting<S>& row : table) {
    if (!row.define) continue;
    std::visit(
        [&](auto member) {
          using V = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<V, double>) {
            o += float_define(row.define, s.*member);
          } else if constexpr (std::is_same_v<V, std::string>) {
            throw runtime_error(row.key + ": a text parameter cannot be a kernel define");
          } else {
            std::snprintf(buf, sizeof buf, " -D%s=%lld", row.define,
                          static_cast<long long>(s.*member));
            o += buf;
          }
        },
        row.member);
  }
  return o;
}

// The group's rows as the parameter table lists them, with each row's type taken from its member
// (so the declared type cannot disagree with what from() reads).
template <class S>
std::vector<ParamSpec> settings_specs(const SettingsTable<S>& table) {
  std::vector<ParamSpec> specs;
  for (const Setting<S>& row : table) {
    ParamSpec spec{row.key,       ParamType::kReal, row.default_value, row.unit,
                   row.min_value, row.max_value,    row.choices,       row.help};
    std::visit(
        [&](auto member) {
          using V = std::remove_cvref_t<decltype(std::declval<S&>().*member)>;
          if constexpr (std::is_same_v<V, double>) {
            spec.type = ParamType::kReal;
          } else if constexpr (std::is_same_v<V, bool>) {
            spec.type = ParamType::kBool;
          } else if constexpr (std::is_same_v<V, std::string>) {
            spec.type = ParamType::kString;
          } else {
            spec.type = ParamType::kInteger;
          }
        },
        row.member);
    specs.push_back(std::move(spec));
  }
  return specs;
}

}  // namespace runnel
