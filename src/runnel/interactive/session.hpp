// SPDX-License-Identifier: MIT
#pragma once
#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/interactive/session_log.hpp"
#include "runnel/models/model.hpp"

namespace runnel {

// An interactive session on one terrain (runnel-viewer without the window): the running model
// and what a user does to it (paint rain, place sources, undo a stroke, switch the scenario's rain,
// switch model, reset), each logged at the step it takes effect before, so that a replay of the
// log reproduces the session bit for bit. Undo keeps the state at the beginning of each of the
// last kUndoDepth strokes.
class Session {
 public:
  static constexpr std::size_t kUndoDepth = 8;

  // A session from a scenario (params and its terrain) or from a checkpoint (any model's).
  Session(ComputeContext& compute, const Parameters& params, const Heightmap& terrain,
          const std::string& input, bool global_rain);
  Session(ComputeContext& compute, const CheckpointData& checkpoint, const std::string& input,
          bool global_rain);

  Model& model() { return *model_; }
  // Counts the models the session has made (a reset or a switch makes a new one).
  std::uint64_t model_generation() const { return generation_; }
  const SessionLog& log() const { return log_; }

  // User actions; each takes effect before the next step and is logged.
  void begin_stroke();
  void set_rain(const std::vector<RainDisc>& discs);  // brush (while painting), then sources
  void end_stroke();
  bool undo();  // false when there is nothing to undo
  void set_global_rain(bool on);
  // Sets a mask of the ground on the disc: "erodibility" (0 frozen … 1) or "rain" (the fraction of
  // the scenario's rain, when it has a rain mask); false (and nothing logged) when the model's
  // ground has no such mask.
  bool paint_mask(const RainDisc& disc, double value, const std::string& mask = "erodibility");
  bool has_mask(const std::string& mask);
  void switch_model(const std::string& name);
  void reset();
  void end();  // logs the end (at exit)

  bool global_rain() const { return global_rain_; }
  const std::vector<RainDisc>& rain() const { return discs_; }
  std::size_t undo_depth() const { return undo_.size(); }
  bool painting() const { return painting_; }
  // The model's rain volume (m³) when the current stroke began (0 before the first stroke).
  double stroke_start_volume() const { return stroke_start_volume_; }

  // Replay: the events of `log` take effect as the model reaches their steps; user actions are then
  // not logged. replay_finished(): the log's end was reached.
  void start_replay(const SessionLog& log);
  bool replaying() const { return replay_.has_value(); }
  bool replay_finished() const { return replay_finished_; }

  // One model step (replayed events due before it applied first); returns the step's length.
  double step();
  // Steps until the model's clock has advanced by `dt` (an iteration model: round(dt) steps), as
  // Model::advance, with the replayed events between steps.
  void advance(double dt);

 private:
  void make_start_model();
  void apply(const SessionEvent& e);
  void record(SessionEvent e);
  void apply_due_events();
  void apply_inputs();  // the painted rain and the rain switch onto a new or restored model

  ComputeContext& compute_;
  Parameters params_;
  Heightmap start_terrain_;
  std::unique_ptr<CheckpointData> start_checkpoint_;
  std::unique_ptr<Model> model_;
  SessionLog log_;
  std::vector<RainDisc> discs_;
  bool global_rain_ = true, painting_ = false;
  double stroke_start_volume_ = 0;
  std::deque<CheckpointData> undo_;
  std::optional<SessionLog> replay_;
  std::size_t replay_next_ = 0;
  bool replay_finished_ = false;
  std::uint64_t generation_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace runnel
