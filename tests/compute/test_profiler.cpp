// SPDX-License-Identifier: MIT
// The profiler books the device's idle time between launches to the kernel that waited, and writes
// every launch to a Chrome trace when asked.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "runnel/compute/kernel.hpp"
#include "test_support.hpp"

using namespace runnel;

namespace {

const char* kSource = R"CL(
__kernel void first(__global float* values, const uint n) {
  if (get_global_id(0) < n) values[get_global_id(0)] += 1.0f;
}
__kernel void second(__global float* values, const uint n) {
  if (get_global_id(0) < n) values[get_global_id(0)] *= 2.0f;
}
)CL";

// A context of its own, whose profiler sees only these tests' launches; never destroyed, as in
// test_support.cpp.
ComputeContext& compute() {
  static ComputeContext& c = *new ComputeContext(test::test_device());
  return c;
}

// The number after "key": in `text`, from `from` on; -1 when absent.
double number_after(const std::string& text, const std::string& key, std::size_t from) {
  const std::size_t at = text.find("\"" + key + "\": ", from);
  return at == std::string::npos ? -1 : std::stod(text.substr(at + key.size() + 4));
}

}  // namespace

TEST(KernelProfiler, BooksTheDevicesIdleTimeToTheKernelThatWaited) {
  cl::Program program = compute().build_source(kSource, "");
  Kernel first(compute(), program, "first"), second(compute(), program, "second");
  cl::Buffer values(compute().context(), CL_MEM_READ_WRITE, 64 * sizeof(float));
  first.set("values", values).set("n", cl_uint{64});
  second.set("values", values).set("n", cl_uint{64});
  const std::string trace = (std::filesystem::temp_directory_path() /
                             ("runnel_trace_" + std::to_string(::getpid()) + ".json"))
                                .string();
  KernelProfiler& profiler = compute().profiler();
  profiler.reset();
  profiler.enable(true);
  profiler.trace_to(trace);
  const auto begin = std::chrono::steady_clock::now();
  first.launch(64);
  compute().queue().finish();  // the device has nothing left to do
  // The host busy elsewhere before the next launch: the gap the profiler must see (not a wait for
  // an event; however loaded the machine, the device cannot start `second` before it is enqueued).
  const double host_busy = 0.05;
  std::this_thread::sleep_for(std::chrono::duration<double>(host_busy));
  second.launch(64);
  profiler.collect();
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  profiler.close_trace();
  profiler.enable(false);

  EXPECT_EQ(profiler.calls().at("first"), 1);
  EXPECT_EQ(profiler.calls().at("second"), 1);
  EXPECT_EQ(profiler.waits().at("first"), 0.0);  // nothing ran before it
  const double waited = profiler.waits().at("second");
  // At least the host's busy time (half of it, for the device clock's granularity), at most what
  // the host saw pass in all.
  EXPECT_GE(waited, 0.5 * host_busy);
  EXPECT_LE(waited, elapsed);

  std::ifstream in(trace);
  std::stringstream text;
  text << in.rdbuf();
  const std::string json = text.str();
  std::filesystem::remove(trace);
  ASSERT_FALSE(json.empty());
  EXPECT_EQ(json.front(), '[');
  EXPECT_EQ(json.substr(json.size() - 2), "]\n");
  const std::size_t first_event = json.find("\"name\": \"first\"");
  const std::size_t second_event = json.find("\"name\": \"second\"");
  ASSERT_NE(first_event, std::string::npos) << json;
  ASSERT_NE(second_event, std::string::npos) << json;
  EXPECT_LT(first_event, second_event);  // in launch order
  EXPECT_NEAR(number_after(json, "wait_us", second_event), 1e6 * waited, 1.0);
  // The second starts after the first ends, by the wait.
  const double first_end =
      number_after(json, "ts", first_event) + number_after(json, "dur", first_event);
  EXPECT_NEAR(number_after(json, "ts", second_event) - first_end, 1e6 * waited, 1.0);
}

TEST(KernelProfiler, ATraceFileThatCannotBeWrittenIsRefusedByName) {
  try {
    compute().profiler().trace_to("/nonexistent-folder/trace.json");
    FAIL() << "an unwritable trace file was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/trace.json"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(compute().profiler().tracing());
}
