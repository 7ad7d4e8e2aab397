// SPDX-License-Identifier: MIT
// runnel-viewer: watch the terrain erode and paint rain with the mouse.
#include <CLI/CLI.hpp>
#include <iostream>

#include "app.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"

int main(int argc, char** argv) {
  runnel::viewer::ViewerOptions o;
  std::string size = "1280x800";
  CLI::App app{
      "runnel-viewer: the SPH rain-erosion simulation live in a window; paint rain with the left "
      "mouse "
      "button. Right drag orbits, middle drag pans, the wheel zooms (ctrl/shift + wheel: brush "
      "radius); "
      "space pause, N step, R reset, S save checkpoint, P screenshot, H help, Esc quit."};
  app.add_option("input", o.input,
                 "scenario (.toml) or checkpoint (.h5); default: built-in defaults");
  app.add_option("--frames", o.frames, "run this many frames, then exit")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--screenshot", o.screenshot, "save the last frame as PNG");
  app.add_option("--stats-every", o.stats_every, "print a JSON line of statistics every K frames")
      ->check(CLI::NonNegativeNumber);
  bool no_rain = false;
  app.add_flag("--no-rain", no_rain, "start with global rain off (paint it)");
  app.add_option("--size", size, "window size WxH")->capture_default_str();
  std::string overlay = "none";
  app.add_option("--overlay", overlay, "terrain overlay at start: none, erosion, water or speed")
      ->check(CLI::IsMember({"none", "erosion", "water", "speed"}))
      ->capture_default_str();
  app.add_option("--device", o.device, "OpenCL device (see 'runnel devices')");
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
    o.overlay = overlay == "erosion" ? 1 : overlay == "water" ? 2 : overlay == "speed" ? 3 : 0;
    return runnel::viewer::run_viewer(o);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "runnel-viewer: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument&) {
    std::cerr << "runnel-viewer: --size " << size << ": expected WxH\n";
    return 2;
  } catch (const runnel::Error& e) {
    std::cerr << "runnel-viewer: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << "runnel-viewer: " << e.what() << "\n";
    return 1;
  }
}
