// SPDX-License-Identifier: MIT
#include "runnel/sim/hydrograph.hpp"

#include <bit>
#include <cmath>
#include <cstdio>

namespace runnel {
namespace {

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// The names of the recorder's place among a checkpoint's counters (doubles by their bits).
const char* const kNext = "hydrograph_next";
const char* const kTime = "hydrograph_time_bits";
const char* const kRain = "hydrograph_rain_bits";
const char* const kOut = "hydrograph_outflow_bits";
const char* const kEdgeOut[4] = {"hydrograph_west_bits", "hydrograph_east_bits",
                                 "hydrograph_north_bits", "hydrograph_south_bits"};

}  // namespace

Hydrograph::Hydrograph(double every, bool per_edge, double t0, const WaterBudget& start)
    : every_(every), per_edge_(per_edge), last_t_(t0), last_(start) {
  text_ = "t,rain,outflow,stored,rain_volume,outflow_volume";
  if (per_edge_)
    for (const char* edge : kEdgeNames) text_ += std::string(",outflow_") + edge;
  text_ += "\n";
  if (active()) next_ = static_cast<long long>(std::floor(t0 / every_ + 1e-9)) + 1;
}

void Hydrograph::record(double t, const WaterBudget& b) {
  const double span = t - last_t_;
  auto rate = [&](double now, double before) { return span > 0 ? (now - before) / span : 0.0; };
  text_ += number(t) + "," + number(rate(b.rain, last_.rain)) + "," +
           number(rate(b.outflow, last_.outflow)) + "," + number(b.stored) + "," + number(b.rain) +
           "," + number(b.outflow);
  if (per_edge_)
    for (int e = 0; e < 4; ++e) {
      text_ += ',';
      text_ += number(rate(b.edges[e], last_.edges[e]));
    }
  text_ += "\n";
  points_.push_back({t, rate(b.outflow, last_.outflow)});
  last_t_ = t;
  last_ = b;
  // The next sampling time is a whole multiple of `every`, so the times do not drift.
  next_ = static_cast<long long>(std::floor(t / every_ + 1e-9)) + 1;
}

std::string Hydrograph::csv() const {
  return text_;
}

std::vector<std::pair<std::string, std::int64_t>> Hydrograph::place() const {
  if (!active()) return {};
  // (+0 for a zero: the bits of −0 read as a negative count, which a checkpoint refuses.)
  auto bits = [](double v) { return std::bit_cast<std::int64_t>(v == 0 ? 0.0 : v); };
  std::vector<std::pair<std::string, std::int64_t>> c = {{kNext, next_},
                                                         {kTime, bits(last_t_)},
                                                         {kRain, bits(last_.rain)},
                                                         {kOut, bits(last_.outflow)}};
  for (int e = 0; e < 4; ++e) c.emplace_back(kEdgeOut[e], bits(last_.edges[e]));
  return c;
}

void Hydrograph::resume_from(const std::vector<std::pair<std::string, std::int64_t>>& counters) {
  auto find = [&](const char* name) -> const std::int64_t* {
    for (auto& [key, value] : counters)
      if (key == name) return &value;
    return nullptr;
  };
  if (!active() || !find(kNext)) return;
  auto real = [&](const char* name) {
    const std::int64_t* v = find(name);
    return v ? std::bit_cast<double>(*v) : 0.0;
  };
  next_ = *find(kNext);
  last_t_ = real(kTime);
  last_.rain = real(kRain);
  last_.outflow = real(kOut);
  for (int e = 0; e < 4; ++e) last_.edges[e] = real(kEdgeOut[e]);
}

}  // namespace runnel
