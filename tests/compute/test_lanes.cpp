// SPDX-License-Identifier: MIT
// The lane kernels (cl/common.cl's LANES items a work-item) per device: the same bits at every
// width the code offers, every program compiled silently for the x86 CPUs PoCL targets (with and
// without AVX-512), and nothing of a successful build on stderr.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <sstream>

#include "runnel/compute/stderr_capture.hpp"
#include "runnel/core/error.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/grid_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::run_program;
using test::ScratchDir;

constexpr unsigned kWidths[] = {4, 8, 16};

// Models whose steps run lane kernels: the droplets (droplet_move) and the SPH water of each
// solver (water_depth_gather, bed_friction_factors). A batch of 37 droplets and an odd particle
// count leave the last work-item's lanes partly empty.
Parameters lane_case(const std::string& model, const std::string& solver) {
  Parameters p = default_parameters();
  p.set("run.model", model);
  if (!solver.empty()) p.set("sph.solver", solver);
  p.set("rain.max_particles", std::int64_t{397});
  p.set("rain.rate", 2000.0);
  p.set("erosion.morphological_factor", 1000.0);
  p.set("droplet.batch", std::int64_t{37});
  return p;
}

Heightmap lane_terrain() {
  return generate_terrain("fbm", 33, 33, 1.0, 5, {{"relief", 0.6}, {"octaves", 4}});
}

CheckpointData run_at_width(unsigned lanes, const std::string& model, const std::string& solver,
                            int steps) {
  ComputeContext compute(test::test_device(), lanes);
  EXPECT_EQ(compute.lanes(), lanes);
  auto m = make_model(compute, lane_case(model, solver), lane_terrain());
  for (int s = 0; s < steps; ++s) m->step();
  return m->checkpoint();
}

TEST(Lanes, EveryLaneKernelGivesTheSameBitsAtEveryWidth) {
  struct Case {
    std::string model, solver;
    int steps;
  };
  for (const Case& c :
       {Case{"droplet", "", 12}, Case{"sph", "wcsph", 150}, Case{"sph", "dfsph", 60}}) {
    const std::string what = c.model + (c.solver.empty() ? "" : " " + c.solver);
    const CheckpointData at8 = run_at_width(8, c.model, c.solver, c.steps);
    // The case is not trivial: the terrain changed and, for SPH, particles landed.
    EXPECT_NE(at8.height_fixed, at8.initial_fixed) << what;
    if (c.model == "sph") {
      EXPECT_GT(at8.particles.id.size(), 50u) << what;
    }
    for (unsigned lanes : {4u, 16u}) {
      SCOPED_TRACE(what + " at " + std::to_string(lanes) + " lanes against 8");
      test::expect_same_state(at8, run_at_width(lanes, c.model, c.solver, c.steps));
    }
  }
}

TEST(Lanes, TheDeviceChoosesItsWidthAndTheEnvironmentMayOverrideIt) {
  DeviceInfo cpu;
  cpu.type = "CPU";
  for (auto [preferred, lanes] :
       {std::pair{1u, 4u}, {4u, 4u}, {8u, 8u}, {16u, 16u}, {32u, 16u}, {12u, 8u}}) {
    cpu.preferred_float_width = preferred;
    EXPECT_EQ(device_lanes(cpu), lanes) << "a CPU preferring " << preferred << " floats";
  }
  DeviceInfo gpu;
  gpu.type = "GPU";
  gpu.preferred_float_width = 1;
  EXPECT_EQ(device_lanes(gpu), 8u);
  EXPECT_THROW(ComputeContext(test::test_device(), 5), Error);
  ScratchDir dir;
  const auto refused =
      run_cli({"bench", "sph", "--particles", "200", "--steps", "1"}, "RUNNEL_LANES=12");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("RUNNEL_LANES=12"), std::string::npos) << refused.err;
  const auto chosen =
      run_cli({"bench", "sph", "--particles", "200", "--steps", "1"}, "RUNNEL_LANES=4");
  EXPECT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_EQ(test::json_number(chosen.out, "lanes"), 4.0) << chosen.out;
}

// Every program the models build, as given to the device's compiler, once per model and solver.
std::vector<ComputeContext::BuiltProgram> every_program(unsigned lanes) {
  ComputeContext compute(test::test_device(), lanes);
  std::vector<std::pair<std::string, std::string>> cases;
  for (const auto& name : model_names()) cases.emplace_back(name, "");
  cases.emplace_back("sph", "dfsph");
  for (const auto& [model, solver] : cases) {
    auto m = make_model(compute, lane_case(model, solver), lane_terrain());
    for (int s = 0; s < 3; ++s) m->step();
  }
  // Nothing the compiler said about any of them on this device (a warning is a defect here too).
  for (const auto& [name, log] : compute.build_logs()) ADD_FAILURE() << name << ":\n" << log;
  return compute.built_programs();
}

// clang 15 is PoCL's own compiler on Debian 12: the same front end, the same calling-convention
// checks. PoCL compiles with -Dinline= (every helper a real call when the ABI is checked) and the
// target's CPU; without AVX-512 a vector of more than 256 bits crossing a call is a warning
// (clang: "AVX vector return of type ... without 'avx512f' enabled changes the ABI"), and
// "N warnings generated." on stderr.
TEST(KernelPortability, EveryProgramCompilesSilentlyForEveryX86CpuAtEveryWidth) {
  const auto clang = run_program("clang-15", {"--version"});
  if (clang.exit_code != 0)
    GTEST_SKIP() << "clang-15 (scripts/setup.sh installs it) is not on PATH";
  ScratchDir dir;
  // Each CPU with the widest lanes it takes, its float vector width (what PoCL reports as
  // preferred, so what device_lanes() chooses there): x86-64 has SSE2 only; sandybridge AVX;
  // haswell AVX2 (PoCL's target on CPUs without AVX-512); znver2 an AMD EPYC's; skylake-avx512.
  const std::pair<const char*, unsigned> cpus[] = {
      {"x86-64", 4}, {"sandybridge", 8}, {"haswell", 8}, {"znver2", 8}, {"skylake-avx512", 16}};
  int compiled = 0;
  for (unsigned lanes : kWidths) {
    const auto programs = every_program(lanes);
    // The lane kernels' programs among them.
    for (const char* lane_file : {"cl/water_depth.cl", "cl/integrate.cl", "cl/models/droplet.cl"}) {
      EXPECT_TRUE(std::any_of(programs.begin(), programs.end(), [&](const auto& p) {
        return p.name.find(lane_file) != std::string::npos;
      })) << lane_file;
    }
    for (std::size_t k = 0; k < programs.size(); ++k) {
      const std::string source = dir.path("program" + std::to_string(k) + ".cl");
      test::write_text(source, programs[k].source);
      for (const auto& [cpu, widest] : cpus) {
        if (lanes > widest) continue;
        std::vector<std::string> args = {"-x",
                                         "cl",
                                         "-Xclang",
                                         "-finclude-default-header",
                                         "-target",
                                         "x86_64-pc-linux-gnu",
                                         std::string("-march=") + cpu,
                                         "-Dinline=",
                                         "-Xclang",
                                         "-cl-ext=+all",
                                         "-emit-llvm",
                                         "-c",
                                         "-o",
                                         "/dev/null"};
        std::istringstream options(programs[k].options);
        for (std::string o; options >> o;) args.push_back(o);
        args.push_back(source);
        const auto r = run_program("clang-15", args);
        ++compiled;
        EXPECT_EQ(r.exit_code, 0) << programs[k].name << " for " << cpu << " at " << lanes
                                  << " lanes:\n"
                                  << r.err;
        EXPECT_EQ(r.err, "") << programs[k].name << " for " << cpu << " at " << lanes << " lanes";
      }
    }
  }
  std::printf("note: %d compilations of runnel's programs, all silent\n", compiled);
}

// What the compiler says in a build that succeeds is kept, not printed; $RUNNEL_KERNEL_LOG prints
// it.
TEST(KernelPortability, ABuildsWarningsAreKeptAndShownOnlyWhenAskedFor) {
  // A source no earlier run built: PoCL's kernel cache would skip the compiler.
  const std::string source =
      "// " + std::to_string(std::random_device{}()) + " " +
      std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) +
      "\n#warning \"a warning the test asked for\"\n"
      "__kernel void noisy(__global int* out) { out[0] = 1; }\n";
  ComputeContext compute(test::test_device());
  StderrCapture quiet;
  compute.build_source(source, "", ComputeContext::Division::exact, "noisy.cl");
  EXPECT_EQ(quiet.release(), "");
  ASSERT_EQ(compute.build_logs().count("noisy.cl"), 1u);
  EXPECT_NE(compute.build_logs().at("noisy.cl").find("a warning the test asked for"),
            std::string::npos);
  setenv("RUNNEL_KERNEL_LOG", "1", 1);
  StderrCapture shown;
  compute.build_source(source, "-DAGAIN", ComputeContext::Division::exact, "noisy.cl");
  const std::string said = shown.release();
  unsetenv("RUNNEL_KERNEL_LOG");
  EXPECT_NE(said.find("noisy.cl"), std::string::npos) << said;
  EXPECT_NE(said.find("a warning the test asked for"), std::string::npos) << said;
}

// A successful run with an empty kernel cache (every program compiled, not loaded) writes nothing
// to stderr: what the compiler says is kept, and shown with $RUNNEL_KERNEL_LOG.
TEST(KernelPortability, ASuccessfulBuildLeavesNothingOnStderr) {
  ScratchDir dir;
  const auto r = run_cli({"bench", "sph", "--particles", "1000", "--steps", "1"},
                         "POCL_CACHE_DIR=" + dir.path("kernels"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(std::filesystem::exists(dir.path("kernels"))) << "the cache was not PoCL's";
}

}  // namespace
}  // namespace runnel
