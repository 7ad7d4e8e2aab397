// SPDX-License-Identifier: MIT
// runnel-viewer under a real X server (Xvfb + Mesa): the screenshot is a rendering of the terrain,
// and a real mouse drag on the terrain (xdotool) paints rain.
#include <gtest/gtest.h>
#include <png.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "test_support.hpp"

namespace runnel {
namespace {

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

// One Xvfb server for the test, on a display number of its own.
class XServer {
 public:
  XServer() {
    // A display number of our own (from the pid), the next one if it is taken. -noreset: an X
    // server resets when its last client leaves, and would refuse connections for a moment.
    for (int attempt = 0; attempt < 8 && !ready(); ++attempt) {
      stop();
      start(100 + getpid() % 800 + 7 * attempt);
    }
  }
  void start(int number) {
    char name[32];
    std::snprintf(name, sizeof name, ":%d", number);
    const std::string cmd =
        "Xvfb " + std::string(name) +
        " -screen 0 1280x900x24 -nolisten tcp -noreset >/dev/null 2>&1 & echo $!";
    FILE* p = popen(cmd.c_str(), "r");
    if (p) {
      if (std::fscanf(p, "%d", &pid_) != 1) pid_ = -1;
      pclose(p);
    }
    display_ = name;
    for (int k = 0; k < 50 && !ready(); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  void stop() {
    if (pid_ > 0) std::system(("kill " + std::to_string(pid_) + " 2>/dev/null").c_str());
    pid_ = -1;
    display_.clear();
  }
  ~XServer() { stop(); }
  // An empty DISPLAY would make xdpyinfo try :0, which another test's server may own.
  // Our own server answers on our display (not another test's, nor a server that lost the display).
  bool ready() const {
    return pid_ > 0 && kill(pid_, 0) == 0 && !display_.empty() &&
           std::system(("DISPLAY=" + display_ + " xdpyinfo >/dev/null 2>&1").c_str()) == 0;
  }
  std::string env() const { return "DISPLAY=" + display_; }
  std::string describe() const {
    return "display " + display_ + ", pid " + std::to_string(pid_) +
           (pid_ > 0 && kill(pid_, 0) == 0 ? " alive" : " gone");
  }

 private:
  std::string display_;
  int pid_ = -1;
};

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

Picture read_rgb_png(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  Picture p;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return p;
  image.format = PNG_FORMAT_RGB;
  p.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, p.rgb.data(), 0, nullptr)) return {};
  p.width = static_cast<int>(image.width);
  p.height = static_cast<int>(image.height);
  return p;
}

#define REQUIRE_X_TOOLS()                                                                          \
  do {                                                                                             \
    if (!std::filesystem::exists(RUNNEL_VIEWER_BINARY))                                            \
      GTEST_SKIP()                                                                                 \
          << "runnel-viewer is not built here (RUNNEL_BUILD_VIEWER=OFF, as in build-asan)";        \
    for (const char* tool : {"Xvfb", "xdotool", "xdpyinfo"}) {                                     \
      if (!have(tool)) GTEST_SKIP() << tool << " is not installed (scripts/setup.sh installs it)"; \
    }                                                                                              \
  } while (0)

TEST(Viewer, ScreenshotShowsTheRenderedTerrain) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string cmd = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + test::source_dir() +
                          "/data/scenarios/default.toml --frames 20 --size 640x480 --screenshot " +
                          dir.path("shot.png") + " > " + dir.path("log.txt") + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.path("log.txt"));
  const Picture p = read_rgb_png(dir.path("shot.png"));
  ASSERT_EQ(p.width, 640);
  ASSERT_EQ(p.height, 480);
  // Not blank: most pixels differ from the sky, and they are terrain colours (green, brown, grey,
  // white).
  std::size_t sky = 0, greenish = 0;
  double mean = 0, mean2 = 0;
  for (std::size_t k = 0; k < p.rgb.size(); k += 3) {
    const int r = p.rgb[k], g = p.rgb[k + 1], b = p.rgb[k + 2];
    sky += std::abs(r - 140) < 6 && std::abs(g - 173) < 6 && std::abs(b - 209) < 6;
    greenish += g > r && g > b;
    const double l = 0.3 * r + 0.59 * g + 0.11 * b;
    mean += l;
    mean2 += l * l;
  }
  const double n = p.rgb.size() / 3.0;
  EXPECT_LT(sky / n, 0.7) << "the terrain covers the view";
  EXPECT_GT(greenish / n, 0.15) << "grass-coloured terrain is visible";
  EXPECT_GT(std::sqrt(mean2 / n - (mean / n) * (mean / n)), 10.0)
      << "shading varies across the picture";
}

// The viewer's stats lines so far ({"frame": ..., "particles": ..., "painting": ...}).
struct StatsLine {
  long long frame = -1, particles = -1;
  bool painting = false;
};
std::vector<StatsLine> read_stats(const std::string& path) {
  std::vector<StatsLine> out;
  std::istringstream lines(test::read_text(path));
  for (std::string line; std::getline(lines, line);) {
    const auto f = line.find("\"frame\": "), at = line.find("\"particles\": ");
    if (f == std::string::npos || at == std::string::npos || line.back() != '}') continue;
    out.push_back({std::stoll(line.substr(f + 9)), std::stoll(line.substr(at + 13)),
                   line.find("\"painting\": true") != std::string::npos});
  }
  return out;
}

// Polls the stats file until `done` holds for the lines read so far, at most `seconds`.
template <typename Done>
bool wait_for_stats(const std::string& path, Done done, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (done(read_stats(path))) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

TEST(Viewer, MouseDragOnTheTerrainPaintsRain) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string stats = dir.path("stats.txt");
  // Global rain off: every particle must come from the brush. The viewer runs until stopped; the
  // test acts on what it reports, never on how long things take.
  const std::string viewer = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + test::source_dir() +
                             "/data/scenarios/default.toml --no-rain --frames 100000 "
                             "--stats-every 5 --size 800x600 > " +
                             stats + " 2>&1 & echo $! > " + dir.path("pid.txt");
  ASSERT_EQ(std::system(viewer.c_str()), 0);
  struct Stop {
    std::string pid_file;
    ~Stop() { std::system(("kill $(cat " + pid_file + ") 2>/dev/null").c_str()); }
  } stop{dir.path("pid.txt")};
  const std::string find =
      x.env() + " xdotool search --sync --name runnel-viewer > " + dir.path("wid.txt");
  ASSERT_EQ(std::system(("timeout 60 sh -c '" + find + "'").c_str()), 0) << "no viewer window";
  // The first stats line: the viewer draws and simulates, and nothing has rained yet.
  ASSERT_TRUE(wait_for_stats(
      stats, [](const auto& l) { return !l.empty(); }, 120))
      << test::read_text(stats);
  EXPECT_EQ(read_stats(stats).front().particles, 0) << "no rain before the drag";

  // Press on the middle of the window (the terrain), drag a little, and hold until the viewer
  // reports painting and rain on the terrain; then release.
  const std::string wid = test::read_text(dir.path("wid.txt"))
                              .substr(0, test::read_text(dir.path("wid.txt")).find('\n'));
  const std::string press = x.env() + " xdotool mousemove --window " + wid +
                            " 560 380 mousedown 1 mousemove --window " + wid + " 600 400";
  ASSERT_EQ(std::system(press.c_str()), 0);
  const bool rained = wait_for_stats(
      stats,
      [](const auto& l) {
        bool painted = false;
        for (const StatsLine& s : l) painted = painted || s.painting;
        return painted && l.back().particles > 50;
      },
      120);
  std::system((x.env() + " xdotool mouseup 1").c_str());
  const auto lines = read_stats(stats);
  bool painted = false;
  for (const StatsLine& s : lines) painted = painted || s.painting;
  EXPECT_TRUE(painted) << "the drag was seen as painting on the terrain";
  EXPECT_TRUE(rained) << test::read_text(stats);
  EXPECT_GT(lines.back().particles, 50) << test::read_text(stats);
}

}  // namespace
}  // namespace runnel
