// SPDX-License-Identifier: MIT
// runnel-viewer's frame: the window (a display's, or EGL's off-screen surface) and the viewer in
// it.
#include "app.hpp"

#include "viewer.hpp"
#include "window.hpp"

namespace runnel::viewer {

int run_viewer(const ViewerOptions& options) {
  Window window(options);
  Viewer viewer(options, window);
  return viewer.loop();
}

}  // namespace runnel::viewer
