// SPDX-License-Identifier: MIT
#include "runnel/terrain/probes.hpp"
#include "runnel/core/text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {

namespace {

using T = ParamType;

const std::vector<ParamSpec>& probe_keys() {
  static const std::vector<ParamSpec> keys = {
      // clang-format off
      {"name", T::kString, "\"\"", "", 0, 0, {}, "the gauge's name in probes.csv (letters, digits, _ and -; unique)"},
      {"x", T::kReal, "0", "m", -1e12, 1e12, {}, "map x (east) of the gauge, in the terrain's georeferencing"},
      {"y", T::kReal, "0", "m", -1e12, 1e12, {}, "map y (north) of the gauge"},
      // clang-format on
  };
  return keys;
}

bool plain_word(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

}  // namespace

std::vector<ParamSpec> probe_parameters() {
  return {
      // clang-format off
      {"probes", T::kEntries, "[]", "", 0, 0, {}, "gauges: [[probes]] points where the run records water surface, depth and bed every run.probe_every into probes.csv (models with water)", &probe_keys()},
      // clang-format on
  };
}

std::vector<Probe> probes_of(const Parameters& params, const Heightmap& terrain) {
  const MapFrame map(terrain);
  const double width = (terrain.nx - 1) * terrain.cell, depth = (terrain.ny - 1) * terrain.cell;
  std::vector<Probe> probes;
  std::set<std::string> names;
  const auto& entries = params.entries("probes");
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const std::string where = "probes[" + std::to_string(k + 1) + "]";
    Probe p;
    p.name = std::get<std::string>(entries[k].at("name"));
    if (!plain_word(p.name))
      throw input_error(where + ".name: " + quoted(p.name) +
                        " must be a non-empty word of letters, digits, _ and -");
    if (!names.insert(p.name).second)
      throw input_error(where + ".name: a probe named " + quoted(p.name) + " is already defined");
    const double mx = entry_real(entries[k], "x"), my = entry_real(entries[k], "y");
    p.x = map.world_x(mx);
    p.z = map.world_z(my);
    if (p.x < 0 || p.x > width || p.z < 0 || p.z > depth)
      throw input_error(where + ": (" + format_number(mx) + ", " + format_number(my) +
                        ") lies off the terrain (map x " + format_number(map.x(0)) + " to " +
                        format_number(map.x(width)) + ", y " + format_number(map.y(depth)) +
                        " to " + format_number(map.y(0)) + ")");
    probes.push_back(p);
  }
  return probes;
}

namespace {

// The depth field on the bed's grid, for surface_height; empty when the model has no water.
Heightmap water_field(const Heightmap& bed, const std::vector<float>& depth) {
  Heightmap water;
  water.nx = bed.nx, water.ny = bed.ny, water.cell = bed.cell;
  water.h = depth;
  return water;
}

ProbeReading read_on(const Heightmap& bed, const Heightmap& water, const Probe& probe) {
  ProbeReading r;
  r.bed = surface_height(bed, probe.x, probe.z);
  r.depth = water.h.empty() ? 0.0 : surface_height(water, probe.x, probe.z);
  r.surface = r.bed + r.depth;
  return r;
}

}  // namespace

ProbeReading read_probe(const Heightmap& bed, const std::vector<float>& depth, const Probe& probe) {
  return read_on(bed, water_field(bed, depth), probe);
}

ProbeRecorder::ProbeRecorder(std::vector<Probe> probes, double every)
    : probes_(std::move(probes)), every_(every), text_("t,name,surface,depth,bed\n") {}

void ProbeRecorder::record(double t, const Heightmap& bed, const std::vector<float>& depth) {
  auto number = [](double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6f", v);
    return std::string(text);
  };
  const Heightmap water = water_field(bed, depth);  // once for every gauge
  for (const Probe& p : probes_) {
    const ProbeReading r = read_on(bed, water, p);
    text_ += number(t) + "," + p.name + "," + number(r.surface) + "," + number(r.depth) + "," +
             number(r.bed) + "\n";
    ++rows_;
  }
  // The next sampling time is a whole multiple of `every`, so the times do not drift.
  taken_ = static_cast<long long>(std::floor(t / every_ + 1e-9)) + 1;
}

std::string ProbeRecorder::csv() const {
  return text_;
}

}  // namespace runnel
