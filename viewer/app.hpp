// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/models/sph_simulation.hpp"

namespace runnel::viewer {

struct ViewerOptions {
  std::string input;  // scenario (.toml) or checkpoint (.h5); empty: built-in defaults
  std::string device;
  int width = 1280, height = 800;
  long long frames = 0;       // 0: until the window closes
  std::string screenshot;     // PNG of the last frame
  long long stats_every = 0;  // JSON line on stdout every K frames
  bool rain = true;           // global rain at start
  int overlay = 0;  // terrain overlay at start: 0 none, 1 erosion, 2 water depth, 3 flow speed
};

// Runs the viewer; returns the process exit code.
int run_viewer(const ViewerOptions& options);

}  // namespace runnel::viewer
