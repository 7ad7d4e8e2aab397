// SPDX-License-Identifier: MIT
// runnel-viewer under a real X server (Xvfb + Mesa): the screenshot is a rendering of the terrain,
// and a real mouse drag on the terrain (xdotool) paints rain.
#include <gtest/gtest.h>
#include <png.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "runnel/models/checkpoint.hpp"
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

// Bad files and names are refused with one line and exit 2 before a window opens (no display
// needed).
TEST(Viewer, BadFlagsAreRefusedBeforeAWindowOpens) {
  if (!std::filesystem::exists(RUNNEL_VIEWER_BINARY))
    GTEST_SKIP() << "runnel-viewer is not built here (RUNNEL_BUILD_VIEWER=OFF, as in build-asan)";
  test::ScratchDir dir;
  test::write_text(dir.path("bad.json"), R"({"runnel_session_log": 1, "model": "sph"})");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--replay", dir.path("missing.json")}, "missing.json: cannot read the session log"},
      {{"--replay", dir.path("bad.json")}, "bad.json: missing or mistyped entry"},
      {{"--model", "nope"}, "model 'nope' is unknown"},
      {{dir.path("nothing.toml")}, "nothing.toml: cannot read the input (no such file)"},
      {{dir.path("bad.json"), "--save-at-exit", dir.path("bad.json")}, "is the input"},
      {{"--screenshot-scale", "20"}, "--screenshot-scale"},
      {{"--headless"}, "--headless: give --frames N or --replay LOG"},
      {{"--sim-share", "1"}, "--sim-share"},
      {{"--sim-share", "nan"}, "--sim-share: must be a number from 0.1 to 0.95 (got nan)"},
      {{"--record-fps", "nan"}, "--record-fps"},
      {{"--record-interval", "nan"}, "--record-interval"},
      {{"--frames", "1e20"}, "--frames"},
      {{"--frames", "2000000000"}, "--frames: must be a number from 0 to 1e+09"},
  };
  for (const auto& [args, expected] : cases) {
    const auto r = test::run_program(RUNNEL_VIEWER_BINARY, args, "DISPLAY=");
    EXPECT_EQ(r.exit_code, 2) << args.front() << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_LT(r.err.size(), 200u) << "no bound printed with DBL_MAX's digits: " << r.err;
  }
}

// With no display at all (DISPLAY unset), --headless draws through EGL the picture the windowed
// viewer draws under X: the same scene, pixel for pixel within rounding, and its benchmark line.
TEST(Viewer, HeadlessDrawsThePictureAWindowDrawsWithoutADisplay) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string scene = test::source_dir() + "/data/scenarios/default.toml --frames 3 " +
                            "--size 640x480 --paused --screenshot ";
  const std::string windowed = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + scene +
                               dir.path("window.png") + " > " + dir.path("log.txt") + " 2>&1";
  ASSERT_EQ(std::system(windowed.c_str()), 0) << test::read_text(dir.path("log.txt"));
  const test::CliResult headless = test::run_program(
      RUNNEL_VIEWER_BINARY,
      {test::source_dir() + "/data/scenarios/default.toml", "--headless", "--frames", "3", "--size",
       "640x480", "--paused", "--screenshot", dir.path("headless.png")},
      "DISPLAY=");
  ASSERT_EQ(headless.exit_code, 0) << headless.err;
  const Picture a = read_rgb_png(dir.path("window.png")),
                b = read_rgb_png(dir.path("headless.png"));
  ASSERT_EQ(a.width, 640);
  ASSERT_EQ(b.width, 640);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  long differing = 0, terrain = 0;
  for (std::size_t k = 0; k < a.rgb.size(); k += 3) {
    differing += std::abs(a.rgb[k] - b.rgb[k]) + std::abs(a.rgb[k + 1] - b.rgb[k + 1]) +
                     std::abs(a.rgb[k + 2] - b.rgb[k + 2]) >
                 6;
    terrain += a.rgb[k + 1] > a.rgb[k + 2];  // green above blue: not the sky
  }
  EXPECT_GT(terrain, 640 * 480 / 5) << "the picture shows the terrain";
  EXPECT_LT(differing, 640 * 480 / 1000) << "pixels that differ between window and headless";
  const test::CliResult bench =
      test::run_program(RUNNEL_VIEWER_BINARY,
                        {test::source_dir() + "/data/scenarios/default.toml", "--headless",
                         "--bench", "--frames", "8", "--size", "320x240"},
                        "DISPLAY=");
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("\"fps\": "), std::string::npos) << bench.out;
}

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
  EXPECT_LT(sky / n, 0.8) << "the terrain covers the view (framed whole, a diamond in the window)";
  EXPECT_GT(greenish / n, 0.15) << "grass-coloured terrain is visible";
  EXPECT_GT(std::sqrt(mean2 / n - (mean / n) * (mean / n)), 10.0)
      << "shading varies across the picture";
}

// The default view frames the whole terrain with a margin, in a landscape and a portrait window:
// the picture's border is sky all round; and the 31-m hills of the default scenario get no snow.
TEST(Viewer, TheDefaultViewFramesTheWholeTerrainAndASmallReliefHasNoSnow) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  for (const char* size : {"640x480", "400x640"}) {
    const std::string shot = dir.path(std::string(size) + ".png");
    const std::string cmd = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + test::source_dir() +
                            "/data/scenarios/default.toml --no-rain --frames 2 --size " + size +
                            " --screenshot " + shot + " > " + dir.path("log.txt") + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.path("log.txt"));
    const Picture p = read_rgb_png(shot);
    ASSERT_GT(p.width, 0);
    auto is_sky = [&](int i, int j) {
      const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
      return std::abs(p.rgb[k] - 140) < 6 && std::abs(p.rgb[k + 1] - 173) < 6 &&
             std::abs(p.rgb[k + 2] - 209) < 6;
    };
    int edge_terrain = 0, terrain = 0, snow = 0;
    int left = p.width, right = -1, top = p.height, bottom = -1;  // the terrain's extent
    for (int j = 0; j < p.height; ++j)
      for (int i = 0; i < p.width; ++i) {
        const bool edge = i < 4 || j < 4 || i >= p.width - 4 || j >= p.height - 4;
        if (is_sky(i, j)) continue;
        ++terrain;
        edge_terrain += edge;
        left = std::min(left, i);
        right = std::max(right, i);
        top = std::min(top, j);
        bottom = std::max(bottom, j);
        const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
        snow += p.rgb[k] > 215 && p.rgb[k + 1] > 215 && p.rgb[k + 2] > 215;
      }
    EXPECT_EQ(edge_terrain, 0) << size << ": the terrain touches the picture's edge";
    // Framed tight: across 85 % of the picture's width or of its height.
    EXPECT_TRUE(right - left > 0.85 * p.width || bottom - top > 0.85 * p.height)
        << size << ": the terrain spans " << right - left << " x " << bottom - top << " pixels";
    EXPECT_LT(snow, terrain / 500) << size << ": white caps on a 31-m relief";
  }
}

// --screenshot-panel takes the window as it looks, the panel (ImGui's dark window, top left)
// included; a plain --screenshot is the scene alone.
TEST(Viewer, AScreenshotCanIncludeThePanel) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  auto dark_share = [&](const std::string& flags) {
    const std::string cmd = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + test::source_dir() +
                            "/data/scenarios/default.toml --no-rain --frames 2 --size 800x600 " +
                            flags + " > " + dir.path("log.txt") + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.path("log.txt"));
    const Picture p = read_rgb_png(dir.path("shot.png"));
    if (p.width != 800) return -1.0;
    int dark = 0, all = 0;
    for (int j = 20; j < 300; ++j)  // inside where the panel opens
      for (int i = 20; i < 300; ++i, ++all) {
        const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
        dark += p.rgb[k] + p.rgb[k + 1] + p.rgb[k + 2] < 150;
      }
    return static_cast<double>(dark) / all;
  };
  EXPECT_GT(dark_share("--screenshot " + dir.path("shot.png") + " --screenshot-panel"), 0.5);
  EXPECT_LT(dark_share("--screenshot " + dir.path("shot.png")), 0.05);
}

// --bench prints one JSON line with the painting loop's rates (their values are benchmarks, not
// tested); too few frames to time are refused before a window opens.
TEST(Viewer, BenchPrintsTheLoopsRates) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string viewer = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + test::source_dir() +
                             "/data/scenarios/default.toml --size 320x240 --bench";
  ASSERT_EQ(std::system((viewer + " --frames 12 > " + dir.path("out.txt") + " 2>&1").c_str()), 0)
      << test::read_text(dir.path("out.txt"));
  const std::string out = test::read_text(dir.path("out.txt"));
  for (const char* key :
       {"\"fps\": ", "\"simulated_seconds_per_wall_second\": ", "\"draw_share\": ",
        "\"water_share\": ", "\"frames\": 7", "\"solver\": \"wcsph\"", "\"display\": \"glfw\"",
        "\"ms_per_frame\": {\"simulate\": "})
    EXPECT_NE(out.find(key), std::string::npos) << key << " in " << out;
  const int refused =
      std::system((viewer + " --frames 3 > " + dir.path("no.txt") + " 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(refused), 2) << test::read_text(dir.path("no.txt"));
}

// One stats line of the viewer ({"frame": ..., "particles": ..., "painting": ...}), by key.
struct StatsLine {
  std::string text;
  double number(const std::string& key) const { return test::json_number(text, key); }
  bool flag(const std::string& key) const {
    return text.find("\"" + key + "\": true") != std::string::npos;
  }
};
std::vector<StatsLine> read_stats(const std::string& path) {
  std::vector<StatsLine> out;
  std::istringstream lines(test::read_text(path));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("{\"frame\": ", 0) == 0 && line.back() == '}') out.push_back({line});
  }
  return out;
}

// runnel-viewer running in the background on our X server, steered by xdotool; every wait is for
// something the viewer reports (a stats line, its exit), never for a fixed time.
class ViewerProcess {
 public:
  ViewerProcess(const XServer& x, const test::ScratchDir& dir, const std::string& args)
      : x_(x), dir_(dir), stats_(dir.path("stats.txt")) {
    const std::string cmd = "cd " + dir.root().string() + " && " + x.env() + " " +
                            RUNNEL_VIEWER_BINARY + " " + args + " --stats-every 5 > " + stats_ +
                            " 2>&1 & echo $! > " + dir.path("pid.txt");
    started_ = std::system(cmd.c_str()) == 0;
    pid_ = std::stoi(test::read_text(dir.path("pid.txt")));
  }
  ~ViewerProcess() {
    if (running()) kill(pid_, SIGKILL);
  }
  bool running() const {
    // A zombie (exited, not yet reaped by the shell that started it) counts as gone.
    return kill(pid_, 0) == 0 &&
           std::system(("ps -o stat= -p " + std::to_string(pid_) + " | grep -qv Z").c_str()) == 0;
  }
  // The window's id, once it is mapped.
  std::string window() {
    if (!window_.empty()) return window_;
    const std::string find =
        x_.env() + " xdotool search --sync --name runnel-viewer > " + dir_.path("wid.txt");
    if (std::system(("timeout 120 sh -c '" + find + "'").c_str()) != 0) return "";
    const std::string text = test::read_text(dir_.path("wid.txt"));
    window_ = text.substr(0, text.find('\n'));
    return window_;
  }
  std::string log() const { return test::read_text(stats_); }
  std::vector<StatsLine> stats() const { return read_stats(stats_); }
  // Polls the stats until `done` holds for the latest line, at most `seconds`.
  template <typename Done>
  bool wait_for(Done done, double seconds = 180) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
      const auto lines = stats();
      if (!lines.empty() && done(lines.back())) return true;
      if (!running()) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  bool wait_exit(double seconds = 180) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (running() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    return !running();
  }
  bool xdotool(const std::string& args) {
    return std::system((x_.env() + " xdotool " + args).c_str()) == 0;
  }
  // Left button down at (x, y) of the window and a small drag: the brush paints.
  bool press_and_drag(int x, int y) {
    const std::string w = window();
    return xdotool("mousemove --window " + w + " " + std::to_string(x) + " " + std::to_string(y) +
                   " mousedown 1 mousemove --window " + w + " " + std::to_string(x + 15) + " " +
                   std::to_string(y + 8));
  }
  bool key(const std::string& keys) {
    return xdotool("windowfocus " + window()) && xdotool("key " + keys);
  }
  bool ok() const { return started_; }

 private:
  const XServer& x_;
  const test::ScratchDir& dir_;
  std::string stats_, window_;
  bool started_ = false;
  int pid_ = -1;
};

// Paints with the brush at (x, y) until the viewer reports `volume` m³ of water added, then lets
// go and waits for the stroke to end.
void paint(ViewerProcess& v, int x, int y, double volume) {
  ASSERT_FALSE(v.window().empty()) << "no viewer window\n" << v.log();
  ASSERT_TRUE(v.wait_for([](const StatsLine&) { return true; })) << v.log();
  ASSERT_TRUE(v.press_and_drag(x, y));
  const bool painted = v.wait_for(
      [&](const StatsLine& s) { return s.flag("painting") && s.number("rain_volume") >= volume; });
  v.xdotool("mouseup 1");
  ASSERT_TRUE(painted) << "the drag painted " << volume << " m3\n" << v.log();
  ASSERT_TRUE(v.wait_for([](const StatsLine& s) { return !s.flag("painting"); })) << v.log();
}

// Pixels that turned blue-green (blue and green both above red by a margin) from `before` to
// `after`, within `radius` of (x, y) and beyond `far` of it. Grass and soil have red above blue.
struct WaterPixels {
  long near = 0, far = 0;
  long brown = 0;  // changed pixels under the brush that are brown (red above blue and green)
};
WaterPixels new_water(const Picture& before, const Picture& after, int x, int y, int radius,
                      int far) {
  WaterPixels w;
  for (int j = 0; j < after.height; ++j) {
    for (int i = 0; i < after.width; ++i) {
      const std::size_t k = 3 * (static_cast<std::size_t>(j) * after.width + i);
      const int r = after.rgb[k], g = after.rgb[k + 1], b = after.rgb[k + 2];
      const int changed = std::abs(r - before.rgb[k]) + std::abs(g - before.rgb[k + 1]) +
                          std::abs(b - before.rgb[k + 2]);
      const double d = std::hypot(i - x, j - y);
      if (changed >= 40 && d <= radius && r > b + 15 && r >= g) ++w.brown;
      if (changed < 40 || b < r + 25 || g < r + 25) continue;
      w.near += d <= radius;
      w.far += d > far;
    }
  }
  return w;
}

// The water surface appears where the brush rained, and not elsewhere: for SPH particles and for
// the pipe model's water depth. The same camera frames both screenshots.
class ViewerPaints : public ::testing::TestWithParam<std::string> {};

TEST_P(ViewerPaints, WaterAppearsWhereTheBrushRained) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string common = test::source_dir() + "/data/scenarios/default.toml --model " +
                             GetParam() + " --no-rain --size 800x600 ";
  {
    ViewerProcess v(x, dir, common + "--frames 10 --screenshot before.png");
    ASSERT_TRUE(v.wait_exit()) << v.log();
  }
  {
    ViewerProcess v(x, dir, common + "--frames 1000000 --screenshot after.png");
    // The picture is taken while it still rains, once the brush has rained `volume`: the brush
    // rains in simulated time, and under steady rain the water it leaves on the ground does not
    // depend on how fast the machine runs the model (the pipe model's water drains within a
    // simulated second of the stroke's end, so a picture after it would).
    ASSERT_FALSE(v.window().empty()) << "no viewer window\n" << v.log();
    ASSERT_TRUE(v.wait_for([](const StatsLine&) { return true; })) << v.log();
    ASSERT_TRUE(v.press_and_drag(480, 330));
    const double volume = GetParam() == "sph" ? 400.0 : 2000.0;
    ASSERT_TRUE(v.wait_for([&](const StatsLine& s) {
      return s.flag("painting") && s.number("rain_volume") >= volume;
    })) << v.log();
    ASSERT_TRUE(v.key("Escape"));
    ASSERT_TRUE(v.wait_exit()) << v.log();
    v.xdotool("mouseup 1");
  }
  const Picture before = read_rgb_png(dir.path("before.png")),
                after = read_rgb_png(dir.path("after.png"));
  ASSERT_EQ(after.width, 800);
  ASSERT_EQ(before.width, 800);
  const WaterPixels none = new_water(before, before, 480, 330, 100, 250);
  EXPECT_EQ(none.near + none.far, 0);
  const WaterPixels w = new_water(before, after, 480, 330, 100, 250);
  std::printf("measured: %ld water pixels near the stroke, %ld far, %ld brown\n", w.near, w.far,
              w.brown);
  // Measured (printed): the pipe model's water covers 10,700–10,900 pixels there, SPH's
  // 6,400–7,300, idle or with three busy processes on two cores; none before the stroke.
  EXPECT_GT(w.near, 500) << "water-coloured pixels under the brush";
  EXPECT_LT(w.far, w.near / 10) << "little water far from where it rained";
  EXPECT_LT(w.brown, w.near / 5) << "the water under the brush reads as water, not as brown soil";
}

INSTANTIATE_TEST_SUITE_P(Models, ViewerPaints, ::testing::Values("sph", "pipe"));

// The water surface is smooth, not faceted: drawn by its shading normal (--water-normals, black
// where there is no water), neighbouring water pixels' normals differ by a mean square below
// 0.005. The SPH surface measures 0.003; one normal per water-grid vertex held across its texel
// measures 0.0085, and flat-shaded triangles 0.037 (SPH) and 0.016 (pipe): a normal jumps at every
// edge. For SPH (its particles' surface) and the pipe model.
class WaterSurfaceShading : public ::testing::TestWithParam<std::string> {};

TEST_P(WaterSurfaceShading, NeighbouringPixelsNormalsVaryLittle) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const bool sph = GetParam() == "sph";
  // Six seconds of the storm for SPH (dfsph, which takes steps of the flow's length), a minute for
  // the pipe model, whose sheets take that long to gather into water deeper than 2 cm.
  const test::CliResult run = test::run_cli(
      {"run", test::source_dir() + "/data/scenarios/default.toml", "--model", GetParam(), "--set",
       sph ? "sph.solver=dfsph" : "run.seed=1", "--set", sph ? "run.sim_time=6" : "run.sim_time=60",
       "--quiet", "--out", dir.path("storm")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string cmd = x.env() + " " + RUNNEL_VIEWER_BINARY + " " + dir.path("storm/final.h5") +
                          " --paused --frames 2 --size 800x600 --water-normals --screenshot " +
                          dir.path("normals.png") + " > " + dir.path("log.txt") + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.path("log.txt"));
  const Picture p = read_rgb_png(dir.path("normals.png"));
  ASSERT_EQ(p.width, 800);
  auto normal = [&](int i, int j) {
    const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
    return std::array<double, 3>{p.rgb[k] / 127.5 - 1, p.rgb[k + 1] / 127.5 - 1,
                                 p.rgb[k + 2] / 127.5 - 1};
  };
  auto water = [&](int i, int j) {
    const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
    return p.rgb[k] + p.rgb[k + 1] + p.rgb[k + 2] > 30;
  };
  double sum = 0;
  long pairs = 0;
  for (int j = 0; j + 1 < p.height; ++j)
    for (int i = 0; i + 1 < p.width; ++i) {
      if (!water(i, j)) continue;
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (!water(i + di, j + dj)) continue;
        const auto a = normal(i, j), b = normal(i + di, j + dj);
        sum += (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
               (a[2] - b[2]) * (a[2] - b[2]);
        ++pairs;
      }
    }
  ASSERT_GT(pairs, 10000) << "the storm left water to draw";
  EXPECT_LT(sum / pairs, 0.005) << "mean squared normal difference of neighbouring water pixels";
}

INSTANTIATE_TEST_SUITE_P(Models, WaterSurfaceShading, ::testing::Values("sph", "pipe"));

// While the brush paints rain, streaks fall under it: the window captured in the middle of a drag
// (Escape while the button is held, --screenshot-panel) has pale streak pixels around the brush
// that the same view without a drag has not.
TEST(Viewer, RainFallsAsStreaksUnderThePaintingBrush) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string common = test::source_dir() +
                             "/data/scenarios/default.toml --no-rain --size 800x600 "
                             "--screenshot-panel --frames 1000000 --screenshot ";
  auto streak_pixels = [&](const std::string& shot) {
    const Picture p = read_rgb_png(dir.path(shot));
    long pale = 0;
    for (int j = 200; j < 340; ++j)  // the air above the brush, where no water lies
      for (int i = 560 - 90; i < 560 + 90; ++i) {
        const std::size_t k = 3 * (static_cast<std::size_t>(j) * p.width + i);
        pale += p.rgb[k] > 150 && p.rgb[k + 1] > 170 && p.rgb[k + 2] > 170 &&
                p.rgb[k + 2] > p.rgb[k] + 10;
      }
    return p.width == 800 ? pale : -1L;
  };
  {
    ViewerProcess v(x, dir, common + "still.png");
    ASSERT_TRUE(v.wait_for([](const StatsLine&) { return true; })) << v.log();
    ASSERT_TRUE(v.xdotool("mousemove --window " + v.window() + " 560 380"));
    ASSERT_TRUE(v.key("Escape"));
    ASSERT_TRUE(v.wait_exit()) << v.log();
  }
  {
    ViewerProcess v(x, dir, common + "raining.png");
    ASSERT_TRUE(v.wait_for([](const StatsLine&) { return true; })) << v.log();
    ASSERT_TRUE(v.press_and_drag(545, 372));  // ends at (560, 380)
    ASSERT_TRUE(v.wait_for([](const StatsLine& s) { return s.flag("painting"); })) << v.log();
    ASSERT_TRUE(v.key("Escape"));  // the button still held: the last frame paints
    ASSERT_TRUE(v.wait_exit()) << v.log();
    v.xdotool("mouseup 1");
  }
  const long still = streak_pixels("still.png"), raining = streak_pixels("raining.png");
  ASSERT_GE(still, 0);
  EXPECT_GT(raining, still + 80) << "streak pixels: " << raining << " painting, " << still
                                 << " not";
}

// The checkpoint the S key writes (runnel-viewer-sph-step*.h5 in the working folder), read and
// removed once it is there.
CheckpointData take_saved_checkpoint(ViewerProcess& v, const test::ScratchDir& dir) {
  EXPECT_TRUE(v.key("s"));
  for (int k = 0; k < 1200; ++k) {
    for (const auto& e : std::filesystem::directory_iterator(dir.root())) {
      if (e.path().filename().string().rfind("runnel-viewer-sph-step", 0) != 0) continue;
      CheckpointData data = read_checkpoint(e.path().string());  // written atomically
      std::filesystem::remove(e.path());
      return data;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ADD_FAILURE() << "S saved no checkpoint\n" << v.log();
  return {};
}

// A stroke and its undo (ctrl+Z) bring back the terrain bytes, the particles and the step the
// stroke began on. The stroke begins while the simulation is paused (space), so the state it
// began on is the one saved (S) just before. The session log of the same session replays to the
// state at exit of the live one, bit for bit.
TEST(Viewer, UndoRestoresTheTerrainAndTheLogReplaysExactly) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string scenario = test::source_dir() + "/data/scenarios/default.toml";
  {
    ViewerProcess v(x, dir,
                    scenario +
                        " --no-rain --frames 1000000 --size 800x600 --log strokes.json "
                        "--save-at-exit live.h5");
    paint(v, 480, 330, 100.0);  // a first stroke, kept: the undone one begins on eroded ground
    ASSERT_TRUE(v.key("space"));
    ASSERT_TRUE(v.wait_for([](const StatsLine& s) { return s.number("steps_per_second") == 0; }));
    const CheckpointData before = take_saved_checkpoint(v, dir);
    ASSERT_TRUE(v.press_and_drag(420, 300));  // the stroke begins, paused
    ASSERT_TRUE(v.wait_for([](const StatsLine& s) { return s.flag("painting"); })) << v.log();
    ASSERT_TRUE(v.key("space"));
    const double rained = v.stats().back().number("rain_volume");
    const bool painted = v.wait_for([&](const StatsLine& s) {
      return s.number("rain_volume") > rained + 200 && s.number("eroded_volume") > 0;
    });
    v.xdotool("mouseup 1");
    ASSERT_TRUE(painted) << v.log();
    ASSERT_TRUE(v.key("space"));
    ASSERT_TRUE(v.wait_for([](const StatsLine& s) {
      return !s.flag("painting") && s.number("steps_per_second") == 0;
    })) << v.log();
    ASSERT_TRUE(v.key("ctrl+z"));
    ASSERT_TRUE(v.wait_for([](const StatsLine& s) { return s.number("undo_depth") == 1; }))
        << v.log();
    const CheckpointData undone = take_saved_checkpoint(v, dir);
    EXPECT_EQ(undone.steps, before.steps);
    EXPECT_EQ(undone.height_fixed, before.height_fixed) << "the terrain bytes, restored";
    EXPECT_EQ(undone.particles.id, before.particles.id) << "the stroke's water is undone too";
    EXPECT_NE(undone.height_fixed, undone.initial_fixed) << "the kept stroke eroded";
    ASSERT_TRUE(v.key("space"));
    ASSERT_TRUE(v.wait_for([&](const StatsLine& s) {
      return s.number("steps") > static_cast<double>(before.steps) + 200;
    }));
    ASSERT_TRUE(v.key("Escape"));
    ASSERT_TRUE(v.wait_exit()) << v.log();
  }
  const CheckpointData live = read_checkpoint(dir.path("live.h5"));
  {
    ViewerProcess v(x, dir, "--replay strokes.json --size 800x600 --save-at-exit replay.h5");
    ASSERT_TRUE(v.wait_exit(600)) << v.log();
  }
  const CheckpointData replay = read_checkpoint(dir.path("replay.h5"));
  EXPECT_EQ(replay.steps, live.steps);
  EXPECT_EQ(replay.height_fixed, live.height_fixed) << "the replayed terrain, bit for bit";
  EXPECT_EQ(replay.particles.id, live.particles.id);
  EXPECT_NE(test::read_text(dir.path("strokes.json")).find("\"event\": \"undo\""),
            std::string::npos);
}

// --record of N frames gives N frames (PNG folder; with ffmpeg also an H.264 file of N frames), and
// --screenshot-scale 2 a screenshot of twice the window.
TEST(Viewer, RecordingHasOneFramePerFrameAndScreenshotsScale) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string scenario = test::source_dir() + "/data/scenarios/default.toml";
  {
    ViewerProcess v(x, dir,
                    scenario +
                        " --model pipe --frames 12 --size 320x240 --record frames "
                        "--screenshot big.png --screenshot-scale 2");
    ASSERT_TRUE(v.wait_exit()) << v.log();
  }
  int pngs = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path("frames")))
    pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, 12);
  const Picture frame = read_rgb_png(dir.path("frames/frame_000011.png"));
  EXPECT_EQ(frame.width, 320);
  EXPECT_EQ(frame.height, 240);
  const Picture big = read_rgb_png(dir.path("big.png"));
  EXPECT_EQ(big.width, 640);
  EXPECT_EQ(big.height, 480);
  if (!have("ffprobe")) GTEST_SKIP() << "ffmpeg is not installed: the PNG recording was checked";
  // The video keeps the promises of its flags: 10 frames at --record-fps 10, frame k the model at
  // k · --record-interval 0.5 s of its clock (the first step at or after it: the pipe model's steps
  // here are about 0.02 s), not drifting later frame by frame.
  {
    ViewerProcess v(x, dir,
                    scenario +
                        " --model pipe --frames 10 --size 320x240 --record out.mp4 "
                        "--record-interval 0.5 --record-fps 10");
    ASSERT_TRUE(v.wait_exit()) << v.log();
    const auto stats = v.stats();
    ASSERT_FALSE(stats.empty()) << v.log();
    for (const StatsLine& line : stats) {
      const double due = 0.5 * line.number("recorded_frames"), time = line.number("time");
      EXPECT_GE(time, due) << line.text;
      EXPECT_LT(time, due + 0.05) << line.text;
    }
    EXPECT_EQ(stats.back().number("recorded_frames"), 10) << v.log();
  }
  const std::string probe =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,r_frame_rate -of csv=p=0 " +
      dir.path("out.mp4") + " > " + dir.path("count.txt");
  ASSERT_EQ(std::system(probe.c_str()), 0);
  const std::string probed = test::read_text(dir.path("count.txt"));  // "10/1,10"
  EXPECT_EQ(probed.substr(0, probed.find(',')), "10/1") << probed;
  EXPECT_EQ(std::stoi(probed.substr(probed.find(',') + 1)), 10) << probed;
}

// A checkpoint of a grid model opens in the viewer (it used to be refused with exit 2), runs its
// model from where the run stopped: the stats name the model.
TEST(Viewer, OpensAGridModelsCheckpoint) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  const std::string scenario = test::source_dir() + "/data/scenarios/default.toml";
  const auto run = test::run_cli(
      {"run", scenario, "--model", "olsen", "--steps", "5", "--out", dir.path("o"), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ViewerProcess v(x, dir, dir.path("o/final.h5") + " --frames 20 --size 320x240");
  ASSERT_TRUE(v.wait_exit()) << v.log();
  const auto stats = v.stats();
  ASSERT_FALSE(stats.empty()) << v.log();
  EXPECT_NE(stats.back().text.find("\"model\": \"olsen\""), std::string::npos) << v.log();
  EXPECT_GT(stats.back().number("steps"), 5) << "it continues from step 5";
}

TEST(Viewer, MouseDragOnTheTerrainPaintsRain) {
  REQUIRE_X_TOOLS();
  XServer x;
  ASSERT_TRUE(x.ready()) << "Xvfb did not start: " << x.describe();
  test::ScratchDir dir;
  // Scenario rain off: every particle must come from the brush.
  ViewerProcess v(x, dir,
                  test::source_dir() +
                      "/data/scenarios/default.toml --no-rain --frames 1000000 --size 800x600");
  ASSERT_FALSE(v.window().empty()) << "no viewer window\n" << v.log();
  ASSERT_TRUE(v.wait_for([](const StatsLine&) { return true; })) << v.log();
  EXPECT_EQ(v.stats().front().number("particles"), 0) << "no rain before the drag";
  paint(v, 560, 380, 50.0);
  EXPECT_GT(v.stats().back().number("particles"), 0) << v.log();
}

}  // namespace
}  // namespace runnel
