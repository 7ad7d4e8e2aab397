// SPDX-License-Identifier: MIT
// runnel validate: the SPH reference cases, a JSON summary on stdout and CSVs in --out.
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/terrain_source.hpp"
#include "runnel/validation/mobile_bed.hpp"
#include "runnel/validation/overland.hpp"
#include "runnel/validation/stream_power_validation.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel::cli {

namespace {

struct ValidateFlags {
  std::string which, out, device, terrain;
  int resolution = 0;
  double settle = 0;
  std::vector<std::string> sets;
  std::vector<std::string> models;
  OverlandCase overland;  // overland's own flags
};

// The flags only `runnel validate overland` reads.
const std::vector<std::string>& overland_flags() {
  static const std::vector<std::string> flags = {"--length",    "--width", "--slope",
                                                 "--manning-n", "--rain",  "--duration",
                                                 "--recession", "--cell",  "--spacing"};
  return flags;
}

// Rain on a plane against the kinematic wave, every run of the case, as one JSON object.
void print_overland(ComputeContext& compute, const ValidateFlags& opt, const ValidationOptions& v) {
  OverlandCase c = opt.overland;
  if (!opt.models.empty()) c.runs = opt.models;
  c.params = v.params;
  c.out_dir = v.out_dir;
  c.progress = v.progress;
  std::cout << validate_overland(compute, c).str() << "\n";
}

// The stream-power model against its analytic steady states, as JSON on stdout.
void print_stream_power_validation() {
  std::vector<JsonObject> profiles;
  for (double n : {1.0, 2.0, 4.0})
    profiles.push_back(json(stream_power_profile(n)).add("n", n).add("target_theta", 0.5 / n));
  std::vector<JsonObject> grids;
  for (double n : {1.0, 2.0})
    grids.push_back(json(stream_power_grid(41, n, 4)).add("n", n).add("target_theta", 0.5 / n));
  std::cout << JsonObject()
                   .add("case", "stream-power")
                   .add("profile_1d", profiles)
                   .add("grid_2d", grids)
                   .add("hillslope_diffusion", json(hillslope_diffusion()))
                   .str()
            << "\n";
}

// The mobile-bed case once per model, each run in its own folder under --out; one JSON object
// with a summary per run.
void print_mobile_bed_runs(ComputeContext& compute, const ValidationOptions& base,
                           const std::vector<std::string>& models) {
  std::vector<JsonObject> runs;
  for (const std::string& model : models) {
    ValidationOptions v = base;
    v.params.set("run.model", model, "--models");
    if (!base.out_dir.empty()) v.out_dir = (std::filesystem::path(base.out_dir) / model).string();
    runs.push_back(validate_mobile_bed(compute, v).summary().add("model", model));
  }
  std::cout << JsonObject().add("case", "mobile-bed").add("runs", runs).str() << "\n";
}

// The case's options from the flags (each checked), then the case, its summary on stdout.
void validate(const ValidateFlags& opt, const CLI::App& cmd) {
  ValidationOptions v;
  v.resolution = opt.resolution;
  // Given, they must be meaningful; absent (0), each case uses its default.
  if (cmd.count("--resolution") && (opt.resolution < 2 || opt.resolution > 2000))
    throw input_error("--resolution: must be 2 to 2000 (got " + std::to_string(opt.resolution) +
                      ")");
  if (cmd.count("--settle") && !(opt.settle > 0 && opt.settle <= 1e4))
    throw input_error("--settle: must be more than 0 and at most 10000 s");
  if (cmd.count("--settle") && opt.which != "hydrostatic" && opt.which != "erosion-convergence" &&
      opt.which != "overland")
    throw input_error(
        "--settle: only hydrostatic and erosion-convergence settle or rain for a time");
  v.settle_time = opt.settle;
  // The SPH tank cases build their own tank: only the fluid's parameters reach them.
  if (opt.which == "hydrostatic" || opt.which == "dambreak" || opt.which == "droplet")
    require_override_groups(opt.sets, {"sph"}, "validate " + opt.which);
  if (opt.which == "stream-power" && !opt.sets.empty())
    throw input_error("--set: validate stream-power runs its own analytic cases and reads none");
  apply_overrides(v.params, opt.sets);
  if (cmd.count("--models") && opt.which != "mobile-bed" && opt.which != "overland")
    throw input_error("--models: only mobile-bed and overland run with a choice of models");
  if (opt.which == "mobile-bed")
    for (const std::string& m : opt.models)
      if (m != "pipe" && m != "sph")
        throw input_error("--models: mobile-bed runs pipe or sph (got '" + m + "')");
  for (const std::string& flag : overland_flags())
    if (cmd.count(flag) && opt.which != "overland")
      throw input_error(flag + ": only overland takes it");
  if (opt.which == "overland") {
    if (cmd.count("--resolution") || cmd.count("--settle"))
      throw input_error(std::string(cmd.count("--resolution") ? "--resolution" : "--settle") +
                        ": overland takes --cell and --spacing instead");
    OverlandCase c = opt.overland;
    if (!opt.models.empty()) c.runs = opt.models;
    c.check();  // before --out is created
  }
  if (cmd.count("--terrain")) {
    if (opt.which != "erosion-convergence")
      throw input_error("--terrain: only erosion-convergence rains on a terrain");
    if (cmd.count("--resolution"))
      throw input_error("--resolution: not with --terrain (the file sets the terrain's size)");
    // As `runnel run --terrain` reads it: --set terrain.cell=... gives a .png or .npy its cell.
    v.params.set("terrain.file", opt.terrain, "--terrain");
    v.terrain = load_terrain(v.params);
    v.terrain_name = std::filesystem::path(opt.terrain).filename().string();
  }
  if (!opt.out.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.out, ec);
    if (ec) throw input_error("--out " + opt.out + ": cannot create the folder: " + ec.message());
    v.out_dir = opt.out;
  }
  v.progress = isatty(STDERR_FILENO);
  if (opt.which == "stream-power") {  // host-side numerics: no device
    print_stream_power_validation();
    return;
  }
  ComputeContext compute(opt.device);
  if (opt.which == "overland") {
    print_overland(compute, opt, v);
  } else if (opt.which == "mobile-bed" && !opt.models.empty()) {
    print_mobile_bed_runs(compute, v, opt.models);
  } else {
    const ValidationResult r = opt.which == "hydrostatic" ? validate_hydrostatic(compute, v)
                               : opt.which == "dambreak"  ? validate_dambreak(compute, v)
                               : opt.which == "droplet"   ? validate_droplet(compute, v)
                               : opt.which == "mobile-bed"
                                   ? validate_mobile_bed(compute, v)
                                   : validate_erosion_convergence(compute, v);
    std::cout << r.summary_json() << "\n";
  }
  // The charts are the Python package's, drawn from the tables the case wrote.
  const std::vector<std::string> charted = {"hydrostatic", "dambreak", "mobile-bed", "overland"};
  if (!opt.out.empty() && std::find(charted.begin(), charted.end(), opt.which) != charted.end())
    std::fprintf(stderr, "runnel: its figures: python3 -m runnel plot %s\n",
                 terminal_safe(opt.out).c_str());
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto opt = std::make_shared<ValidateFlags>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Run an SPH reference case and compare it with its reference: "
      "hydrostatic (pressure = rho0 g d), dambreak (Koshizuka & Oka 1996) or "
      "droplet (bounce, slide and rest of a lone drop against their analytic "
      "values) or erosion-convergence (the eroded volume against the time step, "
      "the particle size, the spawn height and the speed of sound), or stream-power (the "
      "stream-power model against its analytic steady states: a 1-D channel, a "
      "2-D grid's slope-area relation, the diffusion hillslope), or mobile-bed (the pipe model's "
      "bed load in the dam break over a sand bed of Soares-Frazao et al. 2012: gauges and final "
      "bed against the experiment's repeats), or overland (rain on a walled plane with an open "
      "foot, every model that moves water against the kinematic wave: depths, the outflow "
      "hydrograph, the water stored)");
  cmd->add_option("case", opt->which,
                  "hydrostatic, dambreak, droplet, erosion-convergence, stream-power, mobile-bed "
                  "or overland")
      ->required()
      ->check(CLI::IsMember({"hydrostatic", "dambreak", "droplet", "erosion-convergence",
                             "stream-power", "mobile-bed", "overland"}));
  cmd->add_option("--resolution", opt->resolution,
                  "particles across the length scale (hydrostatic: layers in the "
                  "column, default 16; dambreak: across L, default 20); erosion-convergence: "
                  "terrain vertices per side, default 65; mobile-bed: cells a metre, default 20");
  cmd->add_option(
      "--settle", opt->settle,
      "hydrostatic: seconds the column settles before the last quarter is averaged "
      "(default 50 sqrt(H/g), 10 s); erosion-convergence: seconds of rain (default 20)");
  cmd->add_option("--terrain", opt->terrain,
                  "erosion-convergence: the terrain to rain on (.asc, .png, .npy, .tif or another "
                  "raster GDAL reads; "
                  "default: 65 x 65 fBm hills with 2 m cells; --set terrain.cell=... for a file "
                  "without one); the storm scales with its cell size (60,000 mm/h on 2 m cells)");
  cmd->add_option("--out", opt->out,
                  "folder (created) for the case's tables: pressure.csv, front.csv, mobile-bed's "
                  "flume, run, gauges.csv and profiles.csv, overland's runs and overland.json; "
                  "`python -m runnel plot DIR` draws them");
  cmd->add_option("--set", opt->sets, "parameter key=value (repeatable; see 'runnel params')");
  cmd->add_option("--models", opt->models,
                  "mobile-bed: the models to run it with, each in DIR/MODEL (e.g. pipe,sph; "
                  "default: the scenario's, pipe); overland: the runs (pipes, local-inertial, "
                  "godunov: the pipe model's fluxes; wcsph, dfsph: SPH at each --spacing; "
                  "default: all five)")
      ->delimiter(',');
  OverlandCase& o = opt->overland;
  cmd->add_option("--length", o.length, "overland: the plane's length, m")->capture_default_str();
  cmd->add_option("--width", o.width, "overland: between the side walls, m")->capture_default_str();
  cmd->add_option("--slope", o.slope, "overland: m/m")->capture_default_str();
  cmd->add_option("--manning-n", o.manning_n, "overland: Manning's n of every model, s/m^(1/3)")
      ->capture_default_str();
  cmd->add_option("--rain", o.rain_mm_h,
                  "overland: mm/h (the default makes a sheet about 0.55 m deep at the foot, which "
                  "SPH resolves at 0.1 m)")
      ->capture_default_str();
  cmd->add_option("--duration", o.duration, "overland: seconds of rain (default 2 t_e)");
  cmd->add_option("--recession", o.recession, "overland: seconds run after the rain (default t_e)");
  cmd->add_option("--cell", o.cell, "overland: the terrain's cell, m")->capture_default_str();
  cmd->add_option("--spacing", o.spacings, "overland: SPH's particle spacings, m")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--device", opt->device, "OpenCL device (see 'runnel devices')");
  cmd->callback([opt, cmd] {
    // A case refused once under way (a spacing its hash cannot hold) leaves no --out behind that
    // it created.
    std::error_code ec;
    const bool out_is_new = !opt->out.empty() && !std::filesystem::exists(opt->out, ec);
    try {
      validate(*opt, *cmd);
    } catch (const Error& e) {
      if (out_is_new && e.code() == ExitCode::kUsage) std::filesystem::remove_all(opt->out, ec);
      throw;
    }
  });
}

}  // namespace runnel::cli
