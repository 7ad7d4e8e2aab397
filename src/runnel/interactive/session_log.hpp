// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/models/interaction.hpp"

namespace runnel {

// What happened in an interactive session (runnel-viewer), in order, each at the model step it
// took effect before (the model's steps() then): enough to replay the session exactly
// (`runnel-viewer --replay strokes.json`). docs/viewer.md describes the file.
struct SessionEvent {
  enum class Kind {
    kStrokeBegin,  // the brush went down: the state is kept for undo
    kRain,         // the painted rain changed: `discs` (brush first, then sources) from now on
    kStrokeEnd,    // the brush came up
    kUndo,         // back to the state at the latest kept stroke's beginning
    kGlobalRain,   // the scenario's rain switched `on`
    kModel,        // another `model` takes over the terrain as it is
    kReset,        // back to the session's start
    kMask,         // the ground's `mask` ("erodibility" or "rain") set to `value` on `discs[0]`
    kEnd,          // the session ended here
  };
  Kind kind = Kind::kEnd;
  std::uint64_t step = 0;
  double time = 0;          // the model's clock then (for reading; replay goes by step)
  double wall_seconds = 0;  // since the session began (for reading)
  std::vector<RainDisc> discs;
  bool on = false;
  std::string model;
  double value = 0;                  // kMask: 0 (frozen, or dry) … 1
  std::string mask = "erodibility";  // kMask: which mask
};

struct SessionLog {
  std::string input;        // the scenario or checkpoint the session started from ("" built-in)
  std::string model;        // the model it started with
  bool global_rain = true;  // whether the scenario's rain was on at the start
  std::vector<SessionEvent> events;
};

const char* to_string(SessionEvent::Kind kind);
std::string session_log_json(const SessionLog& log);
void write_session_log(const std::string& path, const SessionLog& log);  // atomically
// Throws an input error naming the file and the problem.
SessionLog read_session_log(const std::string& path);

}  // namespace runnel
