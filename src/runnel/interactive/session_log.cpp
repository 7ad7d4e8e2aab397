// SPDX-License-Identifier: MIT
#include "runnel/interactive/session_log.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"
#include "runnel/core/rain_units.hpp"
#include "runnel/io/atomic_file.hpp"

namespace runnel {
namespace {

using Kind = SessionEvent::Kind;
constexpr std::array<std::pair<Kind, const char*>, 9> kKinds = {
    {{Kind::kStrokeBegin, "stroke_begin"},
     {Kind::kRain, "rain"},
     {Kind::kStrokeEnd, "stroke_end"},
     {Kind::kUndo, "undo"},
     {Kind::kGlobalRain, "global_rain"},
     {Kind::kModel, "model"},
     {Kind::kReset, "reset"},
     {Kind::kMask, "mask"},
     {Kind::kEnd, "end"}}};
constexpr int kFormatVersion = 1;

}  // namespace

const char* to_string(Kind kind) {
  for (auto& [k, name] : kKinds)
    if (k == kind) return name;
  return "?";
}

std::string session_log_json(const SessionLog& log) {
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const SessionEvent& e : log.events) {
    nlohmann::ordered_json j;
    j["event"] = to_string(e.kind);
    j["step"] = e.step;
    j["time"] = e.time;
    j["wall_seconds"] = e.wall_seconds;
    if (e.kind == Kind::kRain || e.kind == Kind::kMask) {
      j["discs"] = nlohmann::ordered_json::array();
      for (const RainDisc& d : e.discs) {
        // The rate in the brush's unit; metres per second as read back exactly (%.17g).
        j["discs"].push_back({{"x_m", d.x},
                              {"z_m", d.z},
                              {"radius_m", d.radius},
                              {"rate_m_per_s", d.rate},
                              {"intensity_mm_per_h", rain_intensity(d.rate)}});
      }
    }
    if (e.kind == Kind::kGlobalRain) j["on"] = e.on;
    if (e.kind == Kind::kMask) {
      j["mask"] = e.mask;
      j["value"] = e.value;
    }
    if (e.kind == Kind::kModel) j["model"] = e.model;
    events.push_back(j);
  }
  nlohmann::ordered_json root;
  root["runnel_session_log"] = kFormatVersion;
  root["input"] = log.input;
  root["model"] = log.model;
  root["global_rain"] = log.global_rain;
  root["events"] = events;
  return root.dump(1) + "\n";
}

void write_session_log(const std::string& path, const SessionLog& log) {
  write_text_atomically(path, session_log_json(log));
}

SessionLog read_session_log(const std::string& path) {
  const std::string text = read_text_input(path, "session log");
  const auto fail = [&](const std::string& what) { return input_error(path + ": " + what); };
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("not JSON (") + e.what() + ")");
  }
  try {
    if (!root.is_object() || root.value("runnel_session_log", 0) != kFormatVersion)
      throw fail("not a runnel session log (version " + std::to_string(kFormatVersion) + ")");
    SessionLog log;
    log.input = root.at("input").get<std::string>();
    log.model = root.at("model").get<std::string>();
    log.global_rain = root.at("global_rain").get<bool>();
    std::uint64_t index = 0;
    for (const auto& j : root.at("events")) {
      SessionEvent e;
      const std::string name = j.at("event").get<std::string>();
      bool known = false;
      for (auto& [k, n] : kKinds) {
        if (name == n) {
          e.kind = k;
          known = true;
        }
      }
      if (!known) throw fail("event " + std::to_string(index) + ": unknown kind \"" + name + "\"");
      e.step = j.at("step").get<std::uint64_t>();
      e.time = j.value("time", 0.0);
      e.wall_seconds = j.value("wall_seconds", 0.0);
      if (e.kind == Kind::kRain || e.kind == Kind::kMask) {
        for (const auto& d : j.at("discs")) {
          RainDisc disc{d.at("x_m").get<double>(), d.at("z_m").get<double>(),
                        d.at("radius_m").get<double>(), d.at("rate_m_per_s").get<double>()};
          if (!(disc.radius > 0) || !std::isfinite(disc.rate))
            throw fail("event " + std::to_string(index) +
                       ": a disc needs radius_m > 0 and a finite rate (negative: a sink)");
          e.discs.push_back(disc);
        }
      }
      if (e.kind == Kind::kGlobalRain) e.on = j.at("on").get<bool>();
      if (e.kind == Kind::kMask) {
        e.value = j.at("value").get<double>();
        e.mask = j.value("mask", std::string("erodibility"));
        if (e.discs.size() != 1 || !(e.value >= 0 && e.value <= 1) ||
            (e.mask != "erodibility" && e.mask != "rain"))
          throw fail("event " + std::to_string(index) +
                     ": a mask event needs one disc, a value in [0, 1] and the mask erodibility "
                     "or rain");
      }
      if (e.kind == Kind::kModel) e.model = j.at("model").get<std::string>();
      log.events.push_back(std::move(e));
      ++index;
    }
    return log;
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("missing or mistyped entry (") + e.what() + ")");
  }
}

}  // namespace runnel
