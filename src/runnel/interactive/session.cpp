// SPDX-License-Identifier: MIT
#include "runnel/interactive/session.hpp"

#include <cmath>

#include "runnel/core/error.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/scenario.hpp"

namespace runnel {

Session::Session(ComputeContext& compute, const Parameters& params, const Heightmap& terrain,
                 const std::string& input, bool global_rain)
    : compute_(compute), params_(params), start_terrain_(terrain), global_rain_(global_rain) {
  make_start_model();
  log_ = {input, model_->info().name, global_rain, {}};
}

Session::Session(ComputeContext& compute, const CheckpointData& checkpoint,
                 const std::string& input, bool global_rain)
    : compute_(compute),
      params_(parse_scenario(checkpoint.parameters_toml, input + " (checkpoint parameters)")),
      start_checkpoint_(std::make_unique<CheckpointData>(checkpoint)),
      global_rain_(global_rain) {
  params_.set("run.model", checkpoint.model);
  make_start_model();
  log_ = {input, model_->info().name, global_rain, {}};
}

void Session::make_start_model() {
  if (start_checkpoint_) {
    model_ = make_model_from_checkpoint(compute_, *start_checkpoint_, log_.input);
    params_.set("run.model", start_checkpoint_->model);
  } else {
    if (!log_.model.empty()) params_.set("run.model", log_.model);
    model_ = make_model(compute_, params_, start_terrain_);
  }
  ++generation_;
  apply_inputs();
}

void Session::apply_inputs() {
  model_->interaction().set_global_rain(global_rain_);
  model_->interaction().set_painted_rain(discs_);
}

void Session::record(SessionEvent e) {
  e.step = model_->steps();
  e.time = model_->time();
  e.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  apply(e);
  if (!replay_) log_.events.push_back(std::move(e));
}

namespace {
SessionEvent event(SessionEvent::Kind kind) {
  SessionEvent e;
  e.kind = kind;
  return e;
}
}  // namespace

void Session::begin_stroke() {
  record(event(SessionEvent::Kind::kStrokeBegin));
}
void Session::set_rain(const std::vector<RainDisc>& discs) {
  if (discs == discs_) return;
  SessionEvent e = event(SessionEvent::Kind::kRain);
  e.discs = discs;
  record(std::move(e));
}
void Session::end_stroke() {
  record(event(SessionEvent::Kind::kStrokeEnd));
}
bool Session::undo() {
  if (undo_.empty()) return false;
  record(event(SessionEvent::Kind::kUndo));
  return true;
}
void Session::set_global_rain(bool on) {
  SessionEvent e = event(SessionEvent::Kind::kGlobalRain);
  e.on = on;
  record(std::move(e));
}
bool Session::has_mask(const std::string& mask) {
  if (mask == "rain") return model_->interaction().has_rain_mask();
  return mask == "erodibility" && model_->ground();
}

bool Session::paint_mask(const RainDisc& disc, double value, const std::string& mask) {
  if (!has_mask(mask)) return false;
  SessionEvent e = event(SessionEvent::Kind::kMask);
  e.discs = {disc};
  e.value = value;
  e.mask = mask;
  record(std::move(e));
  return true;
}

void Session::switch_model(const std::string& name) {
  model_entry(name);  // an unknown name is refused before anything is logged
  SessionEvent e = event(SessionEvent::Kind::kModel);
  e.model = name;
  record(std::move(e));
}
void Session::reset() {
  record(event(SessionEvent::Kind::kReset));
}
void Session::end() {
  record(event(SessionEvent::Kind::kEnd));
}

void Session::apply(const SessionEvent& e) {
  using Kind = SessionEvent::Kind;
  switch (e.kind) {
    case Kind::kStrokeBegin:
      undo_.push_back(model_->checkpoint());
      if (undo_.size() > kUndoDepth) undo_.pop_front();
      painting_ = true;
      stroke_start_volume_ = model_->rain_volume();
      break;
    case Kind::kRain:
      discs_ = e.discs;
      model_->interaction().set_painted_rain(discs_);
      break;
    case Kind::kStrokeEnd:
      painting_ = false;
      break;
    case Kind::kUndo:
      if (undo_.empty()) break;
      model_->restore(undo_.back());
      undo_.pop_back();
      painting_ = false;
      apply_inputs();
      break;
    case Kind::kGlobalRain:
      global_rain_ = e.on;
      model_->interaction().set_global_rain(global_rain_);
      break;
    case Kind::kModel: {
      const Heightmap now = model_->terrain();
      params_.set("run.model", e.model);
      model_ = model_entry(e.model).make(compute_, params_, now);
      ++generation_;
      undo_.clear();  // a checkpoint of another model does not restore this one
      apply_inputs();
      break;
    }
    case Kind::kReset:
      undo_.clear();
      make_start_model();
      break;
    case Kind::kMask: {
      const Heightmap& t = model_->initial_terrain();
      const std::vector<int> vertices = vertices_in_disc(t.nx, t.ny, t.cell, e.discs.front());
      if (e.mask == "rain")
        model_->interaction().paint_rain_mask(vertices, static_cast<float>(e.value));
      else if (Ground* ground = model_->ground())
        ground->paint_mask(vertices, static_cast<float>(e.value));
      break;
    }
    case Kind::kEnd:
      if (replay_) replay_finished_ = true;
      break;
  }
}

void Session::start_replay(const SessionLog& log) {
  if (log.model != log_.model)
    throw input_error("replay: the log starts with the " + log.model +
                      " model, the viewer runs the " + log_.model + " model");
  replay_ = log;
  replay_next_ = 0;
  replay_finished_ = false;
  if (global_rain_ != log.global_rain) {
    global_rain_ = log.global_rain;
    model_->interaction().set_global_rain(global_rain_);
  }
  apply_due_events();
}

void Session::apply_due_events() {
  if (!replay_) return;
  while (replay_next_ < replay_->events.size() && !replay_finished_) {
    const SessionEvent& e = replay_->events[replay_next_];
    if (e.step > model_->steps()) break;
    if (e.step < model_->steps())
      throw runtime_error("replay: event " + std::to_string(replay_next_) + " (" +
                          to_string(e.kind) + ") is due at step " + std::to_string(e.step) +
                          ", but the model is at step " + std::to_string(model_->steps()));
    ++replay_next_;
    apply(e);
  }
  if (replay_next_ == replay_->events.size()) replay_finished_ = true;
}

double Session::step() {
  apply_due_events();
  if (replay_finished_) return 0;
  const double dt = model_->step();
  apply_due_events();
  return dt;
}

void Session::advance(double dt) {
  if (model_->info().clock == ModelClock::kIterations) {
    for (long long k = std::llround(dt); k > 0 && !replay_finished_; --k) step();
    return;
  }
  const double target = model_->time() + dt;
  while (model_->time() < target && !replay_finished_) {
    if (step() <= 0) break;
  }
}

}  // namespace runnel
