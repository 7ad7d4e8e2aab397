// SPDX-License-Identifier: MIT
#pragma once
#include <string>

namespace runnel::viewer {

struct ViewerOptions {
  std::string input;  // scenario (.toml) or checkpoint (.h5); empty: built-in defaults
  std::string model;  // start with this model instead of the scenario's run.model
  std::string device;
  int width = 1280, height = 800;
  long long frames = 0;           // 0: until the window closes (or the replay ends)
  std::string screenshot;         // PNG of the scene at exit
  int screenshot_scale = 1;       // screenshots at this multiple of the window size
  bool screenshot_panel = false;  // --screenshot: the window as it looks, panel included
  long long stats_every = 0;      // JSON line on stdout every K frames
  bool bench = false;             // time the frames after the first few, print one JSON line
  bool rain = true;               // the scenario's rain at start
  int overlay = 0;  // terrain overlay at start: 0 none, 1 erosion, 2 water depth, 3 flow speed
  bool particles = false;      // SPH particles as dots over the water surface
  bool paused = false;         // start paused (space plays)
  double sim_share = 0.75;     // the share of each frame the simulation gets (25 ms to 250 ms)
  bool headless = false;       // EGL with no display: an off-screen surface of the window's size
  bool water_normals = false;  // the water's shading normals as colour, nothing else
  std::string log;             // session log written at exit (strokes.json)
  std::string replay;          // session log to replay
  std::string save_at_exit;    // checkpoint written at exit
  std::string record;          // video (.mp4) or PNG folder, recording from the start
  double record_interval = 0;  // model clock per recorded frame; 0: 0.1 s or 1 iteration
  double record_fps = 25;
};

// --bench leaves out the first frames (the GL's first draws, the model's first steps) from its
// timing.
inline constexpr long long kBenchWarmupFrames = 5;

// Runs the viewer; returns the process exit code.
int run_viewer(const ViewerOptions& options);

}  // namespace runnel::viewer
