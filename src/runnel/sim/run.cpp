// SPDX-License-Identifier: MIT
#include "runnel/sim/run.hpp"
#include "runnel/core/text.hpp"

#include "runnel/sim/series.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "runnel/core/error.hpp"
#include "runnel/core/version.hpp"
#include "runnel/ground/ground_outputs.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/io/images.hpp"
#include "runnel/io/progress.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/sim/hydrograph.hpp"
#include "runnel/sim/output_folder.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/height_steps.hpp"
#include "runnel/terrain/probes.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

std::string status_line(Model& model, double steps_per_second) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "step %llu | %s | t = %.3g%s | %.0f steps/s",
                static_cast<unsigned long long>(model.steps()), model.status().c_str(),
                model.time(), clock_suffix(model.info().clock), steps_per_second);
  return buf;
}

void add_value(JsonObject& o, const std::string& key, const ParamValue& value) {
  if (auto* d = std::get_if<double>(&value))
    o.add(key, *d);
  else if (auto* i = std::get_if<std::int64_t>(&value))
    o.add(key, static_cast<long long>(*i));
  else if (auto* b = std::get_if<bool>(&value))
    o.add(key, *b);
  else
    o.add(key, std::get<std::string>(value));
}

JsonObject parameters_json(const Parameters& params) {
  JsonObject o;
  for (auto& [key, value] : params.values()) add_value(o, key, value);
  for (auto& [key, value] : params.generator_values()) o.add("terrain.set." + key, value);
  for (auto& [key, list] : params.all_entries()) {
    std::vector<JsonObject> entries;
    for (const EntryValues& entry : list) {
      entries.emplace_back();
      for (auto& [k, v] : entry) add_value(entries.back(), k, v);
    }
    o.add(key, entries);
  }
  return o;
}

// The gauges' readings at the model's present state.
void read_gauges(Model& model, ProbeRecorder& probes) {
  probes.record(model.time(), model.terrain(), model.interaction().water_view().depth);
}

}  // namespace

double run_length_in_clock(const Parameters& params, ModelClock clock) {
  if (clock == ModelClock::kYears && params.real("run.sim_years") > 0)
    return params.real("run.sim_years");
  return params.real("run.sim_time");
}

RunOptions run_options_from(const Parameters& params, ModelClock clock) {
  RunOptions o;
  o.until_step = static_cast<std::uint64_t>(params.integer("run.steps"));
  if (o.until_step == 0 && clock == ModelClock::kIterations)
    o.until_step = static_cast<std::uint64_t>(params.integer("run.iterations"));
  o.until_time = run_length_in_clock(params, clock);
  o.report_every = params.integer("run.report_every");
  return o;
}

void require_run_length(const Parameters& params, ModelClock clock) {
  if (params.integer("run.steps") > 0) return;
  if (clock != ModelClock::kIterations && !(run_length_in_clock(params, clock) > 0))
    throw input_error("run.sim_time: must be positive when run.steps is 0");
  if (clock == ModelClock::kIterations && params.integer("run.iterations") <= 0)
    throw input_error("run.iterations: must be positive when run.steps is 0");
}

namespace {

// The model's checkpoint with the run's own place in it (outflow.csv's recorder), so that a resumed
// run goes on writing what the uninterrupted one writes.
CheckpointData checkpoint_of_run(Model& model, const Hydrograph& hydrograph) {
  CheckpointData data = model.checkpoint();
  for (auto& counter : hydrograph.place()) data.model_counters.push_back(counter);
  return data;
}

// The checkpoints this run writes into DIR/checkpoints. Rotation only ever removes files this run
// wrote; checkpoints of another run were refused or removed with the folder (OutputFolder).
class RollingCheckpoints {
 public:
  RollingCheckpoints(const std::filesystem::path& out, int keep)
      : dir_(out / "checkpoints"), keep_(keep) {
    std::error_code ec;
    if (std::filesystem::is_directory(dir_, ec))
      remove_stale_temporaries(dir_.string(), "step_");  // left by a writer that was killed
  }

  void write(const CheckpointData& data) {
    namespace fs = std::filesystem;
    fs::create_directories(dir_);
    char name[64];
    std::snprintf(name, sizeof name, "step_%08llu.h5", static_cast<unsigned long long>(data.steps));
    write_checkpoint((dir_ / name).string(), data);
    written_.push_back(dir_ / name);
    while (written_.size() > static_cast<std::size_t>(keep_)) {
      fs::remove(written_.front());
      written_.erase(written_.begin());
    }
  }

 private:
  std::filesystem::path dir_;
  int keep_;
  std::vector<std::filesystem::path> written_;
};

}  // namespace

namespace {

// Before the first step: the device memory the run will take, and a caution about a stepped
// terrain, so that a user can stop the run and smooth the terrain first (once for the models of a
// comparison, which share the terrain).
void announce(const ComputeContext& compute, Model& model, const HeightSteps& steps, bool quiet) {
  if (!quiet) {
    std::fprintf(stderr,
                 "runnel: %s on %s: at most %.1f MB of device memory (the device has %.0f MB)\n",
                 model.info().name.c_str(), compute.info().name.c_str(), model.device_bytes() / 1e6,
                 static_cast<double>(compute.info().global_memory) / 1e6);
  }
  static std::string last_caution;
  if (const std::string caution = steps.caution(); !caution.empty() && caution != last_caution) {
    last_caution = caution;
    std::fprintf(stderr, "runnel: caution: %s\n", terminal_safe(caution).c_str());
  }
}

// The last state the run knows to be good, kept on the host: a run that stops on a numerical
// failure writes it as failed.h5, to be resumed (with other parameters) rather than started again.
// Taken at the start, with every rolling checkpoint, and otherwise after the first step that ends
// kGoodStateEvery seconds of wall time after the last one: a failure loses at most that much work,
// for one copy of the state (a download) every so often.
struct GoodState {
  static constexpr double kGoodStateEvery = 30.0;  // s of wall time
  CheckpointData data;
  double taken_at = 0;  // s of wall time into the loop
  bool due(double elapsed) const { return elapsed - taken_at >= kGoodStateEvery; }
  void keep(CheckpointData d, double elapsed) {
    data = std::move(d);
    taken_at = elapsed;
  }
};

// Volume is conserved exactly (integer quanta): a balance that no longer closes is a numerical
// failure, stopped like a NaN (the run keeps its last good state).
void require_balance(const Model& model, const MassBalance& m) {
  if (m.residual_quanta != 0)
    throw runtime_error("the mass balance no longer closes at step " +
                        std::to_string(model.steps()) + " (t = " + format_number(model.time()) +
                        "): " + std::to_string(m.residual_quanta) +
                        " quanta unaccounted for; the run is unstable");
}

// What the step loop measured.
struct Stepped {
  std::vector<JsonObject> reports;  // the mass balance every options.report_every steps
  double work = 0;                  // particle-, cell- or droplet-steps
  double wall = 0;                  // s
};

// The steps, with progress, mass-balance reports, rolling checkpoints and the series.
Stepped step_until_done(ComputeContext& compute, Model& model, const RunOptions& options,
                        RollingCheckpoints& checkpoints, SeriesWriter& series,
                        ProbeRecorder& probes, Hydrograph& hydrograph, Progress& progress,
                        GoodState& good) {
  Stepped r;
  if (probes.due(model.time())) read_gauges(model, probes);
  const auto start = std::chrono::steady_clock::now();
  good.keep(checkpoint_of_run(model, hydrograph), 0.0);
  const std::uint64_t first_step = model.steps();
  const double first_time = model.time();
  // A run of a length in time ends on it: its last step is shortened to land there.
  auto done = [&] {
    return options.until_step > 0 ? model.steps() >= options.until_step
                                  : model.reached(options.until_time);
  };
  while (!done()) {
    if (options.until_step > 0)
      model.step();
    else
      model.step_towards(options.until_time);
    r.work += model.step_work();
    const bool report = model.steps() % options.report_every == 0;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double fraction =
        options.until_step > 0
            ? static_cast<double>(model.steps() - first_step) / (options.until_step - first_step)
            : (model.time() - first_time) / (options.until_time - first_time);
    std::string status = status_line(model, (model.steps() - first_step) / std::max(elapsed, 1e-9));
    if (report) {
      const MassBalance m = model.mass_balance();
      require_balance(model, m);
      char buf[160];
      std::snprintf(buf, sizeof buf, " | eroded %.4g m3 | balance %.2e m3 (rel %.1e)", m.eroded,
                    m.residual, m.relative);
      status += buf;
      r.reports.push_back(JsonObject()
                              .add("step", static_cast<long long>(model.steps()))
                              .add("sim_time", model.time())
                              .add("balance", m.json()));
    }
    // The step's row before its checkpoint, which carries the recorder's place past it.
    if (hydrograph.due(model.time())) hydrograph.record(model.time(), *model.water_budget());
    if (options.checkpoint_every > 0 && model.steps() % options.checkpoint_every == 0) {
      CheckpointData data = checkpoint_of_run(model, hydrograph);
      checkpoints.write(data);
      good.keep(std::move(data), elapsed);
    } else if (good.due(elapsed)) {
      good.keep(checkpoint_of_run(model, hydrograph), elapsed);
    }
    series.after_step(model);
    if (probes.due(model.time())) read_gauges(model, probes);
    progress.update(fraction, status, report);
  }
  require_balance(model, model.mass_balance());
  series.finish(model);
  compute.queue().finish();
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// Where the device's time went, from the profiler (metrics.json's kernel_* entries).
JsonObject kernel_report(ComputeContext& compute) {
  JsonObject seconds, launches, waits;
  for (auto& [name, s] : compute.profiler().collect()) seconds.add(name, s);
  // Launches per kernel: with many small launches a step, the device's per-launch cost (on PoCL a
  // wake-up of its worker threads) is a cost of its own, outside every kernel's time.
  for (auto& [name, calls] : compute.profiler().calls()) launches.add(name, calls);
  // The device's idle time between launches, booked to the kernel that waited (profiler.hpp).
  for (auto& [name, s] : compute.profiler().waits()) waits.add(name, s);
  const double idle = compute.profiler().idle_seconds();
  compute.profiler().close_trace();
  compute.profiler().enable(false);
  return JsonObject()
      .add("kernel_seconds", seconds)
      .add("kernel_launches", launches)
      .add("kernel_waits", waits)
      .add("device_idle_seconds", idle);
}

// The run's pictures, terrains and maps (README: "what each output file means"); returns the
// final terrain's drainage area, which the metrics use too.
std::vector<double> write_terrain_outputs(const std::filesystem::path& out, Model& model,
                                          const Heightmap& final_terrain) {
  const Heightmap& initial = model.initial_terrain();
  const Heightmap reference = model.erosion_reference();  // the initial one, or uplifted
  const float lo = std::min(initial.min_height(), final_terrain.min_height());
  const float hi = std::max(initial.max_height(), final_terrain.max_height());
  // A terrain with NODATA holes says what their colour means in the title.
  const std::string nodata = initial.georef.holes.empty() ? "" : " (magenta: no data)";
  write_png_rgb((out / "height_initial.png").string(),
                with_title(terrain_picture(initial, lo, hi), "initial terrain" + nodata));
  write_png_rgb((out / "height_final.png").string(),
                with_title(terrain_picture(final_terrain, lo, hi),
                           "after " + std::to_string(model.steps()) + " steps" + nodata));
  write_png_rgb(
      (out / "erosion.png").string(),
      with_title(erosion_picture(reference, final_terrain, erosion_scale(reference, final_terrain)),
                 "erosion and deposition"));
  write_terrain((out / "final.asc").string(), final_terrain);
  write_terrain((out / "final.npy").string(), final_terrain);
  // GeoTIFF with the input's CRS, corner and NODATA value: they overlay the input in a GIS.
  write_terrain((out / "final.tif").string(), final_terrain);
  write_terrain((out / "erosion.tif").string(), height_change(reference, final_terrain));
  // The D8 drainage area of the final terrain (m², docs/metrics.md), as a map for analysis.
  Heightmap drainage(final_terrain.nx, final_terrain.ny, final_terrain.cell);
  std::vector<double> area = metrics::flow_accumulation(final_terrain);
  for (std::size_t k = 0; k < area.size(); ++k) drainage.h[k] = static_cast<float>(area[k]);
  drainage.georef.holes = final_terrain.georef.holes;  // NaN there: no data, no area
  write_terrain((out / "drainage_area.npy").string(), drainage);
  return area;
}

// metrics.json: what the run was, what it did, and the mass balance.
JsonObject run_metrics(const ComputeContext& compute, Model& model, const RunSummary& s,
                       const Stepped& stepped, std::uint64_t first_step, const HeightSteps& steps,
                       const Heightmap& final_terrain) {
  const Parameters& params = model.parameters();
  const Heightmap& initial = model.initial_terrain();
  const MassBalance& m = s.balance;
  return JsonObject()
      .add("runnel_version", kVersion)
      .add("source_revision", kRevision)
      .add("device", compute.info().name)
      .add("lanes", compute.lanes())
      .add("model", model.info().name)
      .add("model_class", model.info().class_name)
      .add("clock", clock_name(model.info().clock))
      .add("seed", static_cast<long long>(params.integer("run.seed")))
      .add("steps", static_cast<long long>(model.steps()))
      .add("sim_time", model.time())
      .add("wall_seconds", stepped.wall)
      .add(std::string(model.work_unit()) + "_per_second",
           stepped.work / std::max(stepped.wall, 1e-9))
      .add("resumed_from_step", static_cast<long long>(first_step))
      .add("rain_volume", s.rain_volume)
      .add("initial_water_volume", model.initial_water_volume())
      .add("eroded_volume", m.eroded)
      .add("deposited_volume", m.deposited)
      .add("outflow_volume", m.outflow)
      .add("suspended_volume", m.suspended)
      .add("lost_volume", m.lost)
      .add("terrain_volume_change", m.terrain_change)
      .add("mass_balance_abs", m.residual)
      .add("mass_balance_rel", m.relative)
      .merge(model.diagnostics())
      .add("terrain", JsonObject()
                          .add("nx", initial.nx)
                          .add("ny", initial.ny)
                          .add("cell", initial.cell)
                          .add("min_height", initial.min_height())
                          .add("max_height", initial.max_height())
                          .merge(steps.json()))
      .add("terrain_metrics", metrics::terrain_metrics_json(s.terrain_values, final_terrain));
}

// A run that stopped on a numerical failure: its last good state as failed.h5 (resumable with
// other parameters: `runnel resume failed.h5 --set ...`) and a metrics.json that says where and
// why it stopped. What the steps wrote so far (probes.csv, outflow.csv) the caller keeps.
void keep_failed_run(const ComputeContext& compute, Model& model, const std::filesystem::path& out,
                     const CheckpointData& good, const std::string& reason) {
  write_checkpoint((out / "failed.h5").string(), good);
  const JsonObject stopped = JsonObject()
                                 .add("reason", reason)
                                 .add("step", static_cast<long long>(model.steps()))
                                 .add("sim_time", model.time())
                                 .add("last_good_checkpoint", "failed.h5")
                                 .add("last_good_step", static_cast<long long>(good.steps))
                                 .add("last_good_sim_time", good.time);
  const JsonObject metrics =
      JsonObject()
          .add("runnel_version", kVersion)
          .add("source_revision", kRevision)
          .add("device", compute.info().name)
          .add("model", model.info().name)
          .add("seed", static_cast<long long>(model.parameters().integer("run.seed")))
          .add("stopped", stopped)
          .add("parameters", parameters_json(model.parameters()));
  write_text_atomically((out / "metrics.json").string(), metrics.str() + "\n");
}

}  // namespace

RunSummary run_model(ComputeContext& compute, Model& model, const RunOptions& options) {
  namespace fs = std::filesystem;
  if (options.particles_every > 0 && model.info().name != "sph") {
    throw input_error("--particles-every: the " + model.info().name + " model has no particles");
  }
  const std::optional<WaterBudget> budget = model.water_budget();
  if (budget && !budget->per_edge && model.parameters().boolean("run.outflow_edges") &&
      model.parameters().real("run.outflow_every") > 0)
    throw input_error("run.outflow_edges: the " + model.info().name +
                      " model counts its outflow over all edges together");
  // Every check of the scenario before the folder is touched (--overwrite empties it).
  std::vector<Probe> gauges = probes_of(model.parameters(), model.initial_terrain());
  const OutputFolder folder(
      options.out_dir, run_identity(parameters_toml(model.parameters()), model.initial_terrain()),
      options.overwrite);
  const fs::path out(options.out_dir);
  RollingCheckpoints checkpoints(out, options.keep_checkpoints);
  const HeightSteps steps = height_steps(model.initial_terrain());
  announce(compute, model, steps, options.quiet);
  compute.profiler().reset();
  // Per-kernel times in metrics.json; always when a trace was asked for (KernelProfiler::trace_to).
  compute.profiler().enable(std::getenv("RUNNEL_NO_PROFILE") == nullptr ||
                            compute.profiler().tracing());
  Progress progress(Progress::mode_for_stderr(options.quiet));
  const std::uint64_t first_step = model.steps();
  // The series grows during the run as series.h5.partial and becomes series.h5 (with its XDMF
  // index) when the run ends: a killed or failed run leaves no partial file under the final name.
  SeriesWriter series(out, options.series_every, options.particles_every, model.initial_terrain());
  ProbeRecorder probes(std::move(gauges), model.parameters().real("run.probe_every"));
  const double outflow_every = budget ? model.parameters().real("run.outflow_every") : 0.0;
  Hydrograph hydrograph(outflow_every, model.parameters().boolean("run.outflow_edges"),
                        model.time(), budget.value_or(WaterBudget{}));
  hydrograph.resume_from(options.resumed_counters);
  series.start(model);
  GoodState good;
  auto write_readings = [&] {
    if (probes.active()) write_text_atomically((out / "probes.csv").string(), probes.csv());
    if (hydrograph.active())
      write_text_atomically((out / "outflow.csv").string(), hydrograph.csv());
  };
  Stepped stepped;
  try {
    stepped = step_until_done(compute, model, options, checkpoints, series, probes, hydrograph,
                              progress, good);
  } catch (const Error& e) {
    if (e.code() != ExitCode::kRuntime) throw;
    progress.abandon();
    series.keep_written();
    std::string kept;
    try {
      write_readings();
      keep_failed_run(compute, model, out, good.data, e.what());
      kept = "; the last good state (step " + std::to_string(good.data.steps) +
             ", t = " + format_number(good.data.time) + ") is in " + (out / "failed.h5").string() +
             ", and metrics.json says where the run stopped";
    } catch (const std::exception& k) {
      kept = std::string("; its last good state could not be kept: ") + k.what();
    }
    throw runtime_error(std::string(e.what()) + kept);
  }
  good = GoodState{};  // before the final checkpoint: one copy of the state at a time
  write_readings();
  const JsonObject kernels = kernel_report(compute);

  write_checkpoint((out / "final.h5").string(), checkpoint_of_run(model, hydrograph));
  const Heightmap final_terrain = model.terrain();
  const std::vector<double> area = write_terrain_outputs(out, model, final_terrain);
  JsonObject ground_report;
  if (Ground* ground = model.ground())
    ground_report = write_ground_outputs(out, *ground, final_terrain);

  RunSummary s;
  s.steps = model.steps();
  s.sim_time = model.time();
  s.wall_seconds = stepped.wall;
  s.balance = model.mass_balance();
  s.rain_volume = model.rain_volume();
  s.terrain_values = metrics::terrain_metric_values(model.initial_terrain(), final_terrain, area);
  s.metrics = run_metrics(compute, model, s, stepped, first_step, steps, final_terrain)
                  .merge(kernels)
                  .add("parameters", parameters_json(model.parameters()))
                  .add("mass_balance_reports", stepped.reports);
  if (model.ground()) s.metrics.add("ground", ground_report);
  write_text_atomically((out / "metrics.json").string(), s.metrics.str() + "\n");
  const MassBalance& m = s.balance;
  char buf[200];
  std::snprintf(
      buf, sizeof buf,
      "%llu steps, t = %.3g%s, eroded %.4g m3, deposited %.4g m3, mass balance %.2e m3 (rel %.1e)",
      static_cast<unsigned long long>(s.steps), s.sim_time, clock_suffix(model.info().clock),
      m.eroded, m.deposited, m.residual, m.relative);
  progress.finish(buf);
  s.caution = model.caution();
  s.model_values = model.summary_values();
  s.hydrograph = hydrograph.points();
  if (!s.caution.empty())
    std::fprintf(stderr, "runnel: caution: %s\n", terminal_safe(s.caution).c_str());
  return s;
}

}  // namespace runnel
