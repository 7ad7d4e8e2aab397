// SPDX-License-Identifier: MIT
// runnel-viewer: watch the terrain erode and paint rain with the mouse.
#include <CLI/CLI.hpp>
#include <charconv>
#include <csignal>
#include <filesystem>
#include <iostream>

#include "app.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"
#include "runnel/core/text.hpp"
#include "runnel/interactive/session_log.hpp"
#include "runnel/io/output_paths.hpp"
#include "runnel/models/registry.hpp"

namespace {

constexpr const char* kAbout =
    "runnel-viewer: any runnel erosion model live in a window (docs/viewer.md). Paint rain with "
    "the left mouse button (brush radius in m, intensity in mm/h in the panel); the water is "
    "drawn as a surface tinted by its sediment load. Right drag orbits, middle drag pans, the "
    "wheel zooms (ctrl/shift + wheel: brush radius); F places a water source, D a sink, C clears "
    "them, "
    "G switches the scenario's rain, ctrl+Z undoes the last stroke, space pauses, N steps, R "
    "resets, Home frames the whole terrain again, S saves a checkpoint, P takes a screenshot, V "
    "records, H helps, Esc quits.";

// A finite number from `min` to `max` (CLI::Range lets NaN through, and prints its bounds with
// all of DBL_MAX's digits).
CLI::Validator number_in(double min, double max) {
  const std::string rule =
      "must be a number from " + runnel::format_number(min) + " to " + runnel::format_number(max);
  return CLI::Validator(
      [min, max, rule](std::string& text) -> std::string {
        double v = 0;
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size() || !(v >= min && v <= max))
          return rule + " (got " + text + ")";
        return "";
      },
      "");
}

// At most a billion frames (six months at 60 frames a second): a count that ends.
constexpr double kMostFrames = 1e9;

// Every flag, with its help and its check.
void declare_options(CLI::App& app, runnel::viewer::ViewerOptions& o, std::string& size,
                     bool& no_rain, std::string& overlay) {
  app.add_option("input", o.input,
                 "scenario (.toml) or checkpoint (.h5) of any model; default: built-in defaults "
                 "(with --replay: the log's)");
  app.add_option("--model", o.model, "start with this model instead of the scenario's run.model");
  app.add_option("--frames", o.frames, "run this many frames, then exit")
      ->check(number_in(0, kMostFrames));
  app.add_option("--screenshot", o.screenshot, "save the scene at exit as PNG");
  app.add_flag(
      "--screenshot-panel", o.screenshot_panel,
      "--screenshot: the window as it looks, the panel included (for a bug report), at the "
      "window's size");
  app.add_option("--screenshot-scale", o.screenshot_scale,
                 "screenshots (P, --screenshot) at N times the window size, for print")
      ->check(number_in(1, 8))
      ->capture_default_str();
  app.add_option("--stats-every", o.stats_every, "print a JSON line of statistics every K frames")
      ->check(number_in(0, kMostFrames));
  app.add_flag("--bench", o.bench,
               "benchmark the painting loop: run --frames frames (default 60), simulating and "
               "drawing, and print one JSON line: frames per second, simulated seconds per wall "
               "second and the share of the time spent drawing, over all frames but the first 5 "
               "(bench/viewer.sh runs it at 20,000 and 200,000 particles)");
  app.add_flag("--no-rain", no_rain, "start with the scenario's rain off (paint it)");
  app.add_flag("--particles", o.particles, "draw the SPH particles as dots over the water");
  app.add_flag("--paused", o.paused, "start paused (space plays)");
  app.add_option("--sim-share", o.sim_share,
                 "the share of each frame's time the simulation gets, the rest drawing (each frame "
                 "simulates 25 ms to 250 ms): lower it for more frames per second on a slow GL, "
                 "raise it for more simulated time")
      ->check(number_in(0.1, 0.95))
      ->capture_default_str();
  app.add_flag("--headless", o.headless,
               "draw with no display or window, through EGL (a GPU server, a CI machine): for "
               "--screenshot, --record and --bench; no mouse or keys, so give --frames or "
               "--replay");
  app.add_flag("--water-normals", o.water_normals,
               "draw only the water, coloured by its shading normal (x, y, z as red, green, "
               "blue) on black: to check the surface's smoothness");
  app.add_option("--size", size, "window size WxH")->capture_default_str();
  app.add_option("--overlay", overlay, "terrain overlay at start: none, erosion, water or speed")
      ->check(CLI::IsMember({"none", "erosion", "water", "speed"}))
      ->capture_default_str();
  app.add_option("--log", o.log,
                 "write the session log (strokes, undo, model switches, with their steps) here "
                 "at exit, for --replay");
  app.add_option("--replay", o.replay,
                 "replay a session log exactly, then exit (painting is off while it plays)");
  app.add_option("--save-at-exit", o.save_at_exit, "write a checkpoint of the final state here");
  app.add_option("--record", o.record,
                 "record from the start: x.mp4 through ffmpeg, or a folder of PNG frames (also "
                 "when ffmpeg is missing); V starts and stops a recording");
  app.add_option("--record-interval", o.record_interval,
                 "model time between recorded frames (s, yr or iterations); default 0.1 s or 1 "
                 "iteration")
      ->check(number_in(0, 1e9));
  app.add_option("--record-fps", o.record_fps, "frame rate of the recorded video")
      ->check(number_in(1.0, 240.0))
      ->capture_default_str();
  app.add_option("--device", o.device, "OpenCL device (see 'runnel devices')");
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe or a file-size limit while recording or saving is a write error, not a signal.
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  runnel::viewer::ViewerOptions o;
  std::string size = "1280x800";
  CLI::App app{kAbout};
  bool no_rain = false;
  std::string overlay = "none";
  declare_options(app, o, size, no_rain, overlay);
  try {
    app.parse(argc, argv);
    const auto x = size.find('x');
    if (x == std::string::npos) throw runnel::input_error("--size " + size + ": expected WxH");
    o.width = std::stoi(size.substr(0, x));
    o.height = std::stoi(size.substr(x + 1));
    if (o.width < 64 || o.height < 64 || o.width > 16384 || o.height > 16384) {
      throw runnel::input_error("--size " + size + ": out of range");
    }
    o.rain = !no_rain;
    if (o.bench && o.frames == 0) o.frames = 60;
    using runnel::viewer::kBenchWarmupFrames;
    if (o.bench && o.frames <= kBenchWarmupFrames)
      throw runnel::input_error("--frames " + std::to_string(o.frames) +
                                ": --bench times the "
                                "frames after the first " +
                                std::to_string(kBenchWarmupFrames));
    if (o.headless && o.frames == 0 && o.replay.empty())
      throw runnel::input_error(
          "--headless: give --frames N or --replay LOG (no window, nothing else ends the run)");
    // Files and names are checked before a window opens: a bad one is refused without a display.
    if (!o.input.empty()) runnel::require_regular_input(o.input, "input");
    if (!o.replay.empty()) runnel::read_session_log(o.replay);
    if (!o.model.empty()) runnel::model_entry(o.model);
    // No output may replace an input or another output (a checkpoint saved over the one opened).
    const bool record_folder = !o.record.empty() && !o.record.ends_with(".mp4");
    runnel::check_output_paths({{"input", o.input}, {"--replay", o.replay}},
                               {{"--save-at-exit", o.save_at_exit},
                                {"--screenshot", o.screenshot},
                                {"--log", o.log},
                                {"--record", record_folder ? std::string() : o.record}});
    o.overlay = overlay == "erosion" ? 1 : overlay == "water" ? 2 : overlay == "speed" ? 3 : 0;
    return runnel::viewer::run_viewer(o);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "runnel-viewer: " << runnel::terminal_safe(e.what()) << "\n";
    return 2;
  } catch (const std::invalid_argument&) {
    std::cerr << "runnel-viewer: --size " << runnel::terminal_safe(size) << ": expected WxH\n";
    return 2;
  } catch (const runnel::Error& e) {
    std::cerr << "runnel-viewer: " << runnel::terminal_safe(e.what()) << "\n";
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << "runnel-viewer: " << runnel::terminal_safe(e.what()) << "\n";
    return 1;
  }
}
