// SPDX-License-Identifier: MIT
// runnel bench: throughput benchmarks that print JSON (never timed tests).
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/validation/sph_benchmark.hpp"

namespace runnel::cli {

void add_bench_command(CLI::App& app) {
  struct Options {
    std::string which, device, trace, scene = "block";
    long long particles = 100000;
    int size = 1024;
    int steps = 20;
    int tile = 0;
    std::vector<std::string> sets;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "bench",
      "Measure throughput and print JSON with per-kernel times from OpenCL "
      "profiling events. sph: N particles in a tank (--scene block or sheet); droplet: "
      "batches of Beyer droplets on a size x size terrain (--steps batches); generate: the "
      "noise generators at size x size vertices (vertices per second)");
  cmd->add_option("model", opt->which,
                  "what to measure: sph, droplet, olsen, thermal, pipe, stream-power or generate")
      ->required()
      ->check(CLI::IsMember(
          {"sph", "droplet", "olsen", "thermal", "pipe", "stream-power", "generate"}));
  cmd->add_option("--size", opt->size, "grid models and generate: terrain vertices per side")
      ->capture_default_str();
  cmd->add_option("--particles", opt->particles, "number of particles")->capture_default_str();
  cmd->add_option("--steps", opt->steps, "timed steps (after 3 warm-up steps)")
      ->capture_default_str();
  cmd->add_option("--tile", opt->tile,
                  "sph: particles of a cell one work-group of the neighbour passes takes; 1 gives "
                  "every particle its own work-item; 0: the device's choice (a CPU 32, a GPU 1)")
      ->capture_default_str();
  cmd->add_option(
         "--scene", opt->scene,
         "sph: block (a block settling in a tank, the pressure solves' hardest case), fall (the "
         "same block dropped from a quarter of its height into a tank twice as wide: it falls, "
         "lands and spreads) or sheet (a film two particles deep running down a 10 % slope, "
         "like most of a storm)")
      ->check(CLI::IsMember({"block", "fall", "sheet"}))
      ->capture_default_str();
  cmd->add_option("--set", opt->sets, "sph.* parameter key=value (repeatable)");
  cmd->add_option("--device", opt->device, "OpenCL device (see 'runnel devices')");
  cmd->add_option("--trace", opt->trace,
                  "write the timed steps' kernel launches to FILE as a Chrome trace (Perfetto, "
                  "chrome://tracing)")
      ->type_name("FILE");
  cmd->callback([opt] {
    if (opt->particles < 8 || opt->particles > 100000000)
      throw input_error("--particles: must be in 8..1e8");
    if (opt->steps < 1 || opt->steps > 1000000) throw input_error("--steps: must be in 1..1e6");
    if (opt->tile < 0 || opt->tile > 256) throw input_error("--tile: must be in 0..256");
    Parameters params = default_parameters();
    if (opt->which == "sph") require_override_groups(opt->sets, {"sph"}, "bench sph");
    apply_overrides(params, opt->sets);
    ComputeContext compute(opt->device);
    if (!opt->trace.empty()) {
      check_output_paths({}, {{"--trace", opt->trace}});
      compute.profiler().trace_to(opt->trace);
    }
    if (opt->which == "generate") {
      if (opt->size < 16 || opt->size > 16384) throw input_error("--size: must be in 16..16384");
      std::cout << benchmark_generators(compute, opt->size, opt->steps).str() << "\n";
      return;
    }
    if (opt->which != "sph") {
      if (opt->size < 16 || opt->size > 16384) throw input_error("--size: must be in 16..16384");
      std::cout << benchmark_model(compute, opt->which, opt->size, opt->steps, params).str()
                << "\n";
      return;
    }
    std::cout
        << benchmark_sph(compute, opt->particles, opt->steps, params, opt->tile, opt->scene).str()
        << "\n";
  });
}

}  // namespace runnel::cli
