// SPDX-License-Identifier: MIT
// The memory figure `runnel run` prints before a grid model starts ("at most N MB of device
// memory") against what the model really takes: on PoCL's CPU device a buffer is host memory, so
// the growth of the process's resident memory while a model is built and takes a step measures its
// buffers independently of the figure. The figure must cover them (it once left out the models'
// own scratch buffers: a third of the pipe's memory).
#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "runnel/core/error.hpp"
#include "runnel/models/memory_check.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// Resident bytes of this process (/proc/self/statm: pages), once the allocator has handed back
// the free memory it keeps: what a kernel compile or a launch's temporaries freed must not count
// as the model's (on a cold PoCL kernel cache the measured step compiles its kernels for the large
// grid, and the growth came out 15 bytes a vertex above the buffers).
double resident_bytes() {
  malloc_trim(0);
  long size = 0, resident = 0;
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return -1;
  const int read = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return read == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE))
                   : -1;
}

// A model by name; "pipe-bedload" is the pipe model at its largest: the bed-load law with the
// talus and the godunov flux.
Parameters parameters(const std::string& model) {
  Parameters p = default_parameters();
  const bool bedload = model == "pipe-bedload";
  p.set("run.model", bedload ? std::string("pipe") : model);
  if (bedload) {
    p.set("pipe.law", std::string("bedload"));
    p.set("pipe.flux", std::string("godunov"));
  }
  return p;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;  // GCC
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;  // clang (build-asan)
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

class DeviceBytes : public ::testing::TestWithParam<std::string> {};

TEST_P(DeviceBytes, TheMemoryFigureCoversWhatTheModelTakes) {
  if (kAddressSanitizer) {
    GTEST_SKIP()
        << "AddressSanitizer's shadow memory and quarantine make resident memory no measure "
           "of buffers";
  }
  if (compute().info().type != "CPU")
    GTEST_SKIP() << "buffers are host memory only on a CPU device";
  const std::string name = GetParam();
  const int side = 1025;  // 1 M vertices: the buffers dwarf everything else the model allocates
  // Compiled once before measuring, on the same grid (PoCL compiles a kernel again for a launch
  // of another size; on a cold kernel cache a warm-up on a small grid left 11-12 bytes a vertex of
  // the compiler's memory in the measured step), so the compiler's memory is not counted. The
  // warm-up model lives on, so that the measured one cannot reuse its freed memory.
  const Heightmap terrain = generate_terrain("fbm", side, side, 1.0, 3, {{"relief", 0.3}});
  auto warm_up = make_model(compute(), parameters(name), terrain);
  warm_up->step();
  compute().queue().finish();
  const double before = resident_bytes();
  ASSERT_GT(before, 0);
  auto model = make_model(compute(), parameters(name), terrain);
  model->step();
  compute().queue().finish();
  const double grown = resident_bytes() - before;
  const double figure = model->device_bytes(), vertices = static_cast<double>(side) * side;
  std::printf("%s: figure %.1f bytes a vertex, resident memory grew %.1f\n", name.c_str(),
              figure / vertices, grown / vertices);
  // The figure counts the host's copy of the initial terrain too (GridState: 12 bytes a vertex),
  // and may exceed the growth by buffers a model allocates but never touches (the terrain's deltas
  // and normals for a model that writes the heights directly: 20 bytes a vertex). Below it by less
  // than one float a vertex (measured: 1.3 bytes at most, page rounding and the launches' own
  // allocations): a buffer the figure forgot fails.
  EXPECT_GE(figure, grown - 3.0 * vertices) << "bytes; the model took " << grown;
  EXPECT_LE(figure, grown + 40.0 * vertices) << "bytes; the model took " << grown;
}

INSTANTIATE_TEST_SUITE_P(GridModels, DeviceBytes,
                         ::testing::Values("droplet", "pipe", "olsen", "thermal"));

// The bound a model is checked against before it allocates anything (a terrain too large for the
// machine is refused there, since PoCL aborts on a failed allocation) must cover the model's
// buffers as it counts them itself, with and without layers. (SPH's figure is mostly its particles
// and its hash grid, which grow with the rain and the relief, not with the vertices: the SPH model
// checks that whole figure against the device itself, once its grid is known.)
class MemoryBound : public ::testing::TestWithParam<std::string> {};

TEST_P(MemoryBound, TheUpFrontBoundCoversTheModelsBuffers) {
  const int side = 129;
  const double vertices = static_cast<double>(side) * side;
  const Heightmap terrain = generate_terrain("fbm", side, side, 1.0, 3, {{"relief", 0.3}});
  Parameters flat = parameters(GetParam());
  const auto plain = make_model(compute(), flat, terrain);
  const double bound = plain->info().device_bytes_per_vertex;
  EXPECT_LE(plain->device_bytes(), memory_need(vertices, bound, false, 0).device_bytes)
      << plain->device_bytes() / vertices << " bytes a vertex";
  Parameters layered = flat;
  layered.add_layer({{"name", std::string("soil")}, {"thickness", 2.0}}, "test");
  layered.add_layer({{"name", std::string("rock")}, {"thickness", 50.0}}, "test");
  const auto with_layers = make_model(compute(), layered, terrain);
  EXPECT_LE(with_layers->device_bytes(), memory_need(vertices, bound, true, 2).device_bytes)
      << with_layers->device_bytes() / vertices << " bytes a vertex with two layers";
}

INSTANTIATE_TEST_SUITE_P(GridModels, MemoryBound,
                         ::testing::Values("droplet", "pipe", "pipe-bedload", "olsen", "thermal",
                                           "stream-power"),
                         [](const auto& info) { return test::param_name(info.param); });

TEST(MemoryBound, ATerrainTooLargeForTheDeviceIsRefusedWithItsSizes) {
  const DeviceInfo& device = compute().info();
  ASSERT_GT(device.global_memory, 0u);
  // Twice the device's memory in vertices: refused before any allocation, exit code 1.
  const double vertices = 2.0 * static_cast<double>(device.global_memory) / 64.0;
  try {
    require_memory(compute(), memory_need(vertices, 64.0, false, 0),
                   "the thermal model on a huge terrain");
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kRuntime);
    EXPECT_NE(std::string(e.what()).find("GB"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the thermal model on a huge terrain"), std::string::npos)
        << e.what();
  }
  // A small terrain passes.
  EXPECT_NO_THROW(require_memory(compute(), memory_need(1e4, 64.0, false, 0), "a small terrain"));
}

}  // namespace
}  // namespace runnel
