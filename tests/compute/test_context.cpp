// SPDX-License-Identifier: MIT
// The OpenCL runtime on PoCL: device selection, embedded kernels, compile errors with file and
// line, and the first real kernel (vertex normals) against its host reference.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/rng.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_normals.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

TEST(ComputeContext, SelectsACpuDeviceByTypeIndexAndName) {
  const auto devices = list_devices();
  ASSERT_FALSE(devices.empty());
  const DeviceInfo cpu = select_device("cpu");
  EXPECT_EQ(cpu.type, "CPU");
  EXPECT_EQ(select_device(std::to_string(cpu.index)).name, cpu.name);
  EXPECT_EQ(
      select_device(std::to_string(cpu.platform_index) + ":" + std::to_string(cpu.device_index))
          .name,
      cpu.name);
  EXPECT_EQ(select_device(cpu.name).name, cpu.name);
  EXPECT_GT(cpu.compute_units, 0u);
  EXPECT_GT(cpu.global_memory, 0ull);
}

TEST(ComputeContext, UnknownDeviceIsAnInputError) {
  for (const char* spec : {"99", "7:7", "no-such-device-anywhere"}) {
    try {
      select_device(spec);
      FAIL() << spec;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage);
      EXPECT_NE(std::string(e.what()).find(spec), std::string::npos);
    }
  }
}

TEST(ComputeContext, CompileErrorNamesFileAndLine) {
  ComputeContext compute("cpu");
  const std::string source =
      "#line 1 \"cl/broken.cl\"\n__kernel void f(__global float* x) {\n  x[0] = undeclared;\n}\n";
  try {
    compute.build_source(source);
    FAIL() << "a broken kernel compiled";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.code(), ExitCode::kRuntime);
    EXPECT_NE(msg.find("cl/broken.cl:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undeclared"), std::string::npos) << msg;
  }
}

TEST(ComputeContext, EveryEmbeddedKernelCompiles) {
  ComputeContext compute(test::test_device());
  EXPECT_NO_THROW(compute.program({"cl/common.cl", "cl/terrain_normals.cl"}));
  EXPECT_NO_THROW(compute.program({"cl/common.cl", "cl/rng_probe.cl"}));
  EXPECT_THROW(embedded_source("cl/nope.cl"), Error);
}

TEST(TerrainNormals, KernelMatchesHostReference) {
  ComputeContext compute(test::test_device());
  TerrainNormals normals(compute);
  const Heightmap t = generate_terrain("fbm", 97, 61, 1.5, 3);
  const auto device = normals.compute(t);
  const auto host = terrain_normals_reference(t);
  ASSERT_EQ(device.size(), host.size());
  for (std::size_t k = 0; k < host.size(); ++k) ASSERT_NEAR(device[k], host[k], 2e-6) << k;
}

TEST(TerrainNormals, PlaneNormalIsAnalytic) {
  ComputeContext compute(test::test_device());
  TerrainNormals normals(compute);
  const Heightmap t = generate_terrain("plane", 9, 9, 1.0, 1, {{"slope", 30.0}, {"azimuth", 90.0}});
  const auto n = normals.compute(t);
  const double s = std::sin(30.0 * M_PI / 180.0), c = std::cos(30.0 * M_PI / 180.0);
  for (std::size_t k = 0; k < t.size(); ++k) {  // rises to the south (+z): n = (0, cos, -sin)
    ASSERT_NEAR(n[3 * k + 0], 0.0, 1e-5);
    ASSERT_NEAR(n[3 * k + 1], c, 1e-5);
    ASSERT_NEAR(n[3 * k + 2], -s, 1e-5);
  }
}

TEST(Rng, DeviceDrawsTheSameBitsAsTheHost) {
  ComputeContext compute(test::test_device());
  Kernel probe(compute, compute.program({"cl/common.cl", "cl/rng_probe.cl"}), "rng_probe");
  const std::size_t n = 4096;
  cl::Buffer bits(compute.context(), CL_MEM_WRITE_ONLY, n * sizeof(cl_ulong));
  cl::Buffer uniform(compute.context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Buffer keyed(compute.context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
  const cl_ulong seed = 0xDEADBEEF12345ULL, stream = 77, key = rng_key(seed, stream, 3);
  probe.set("bits", bits)
      .set("uniform", uniform)
      .set("keyed", keyed)
      .set("seed", seed)
      .set("stream", stream);
  probe.set("key", key).launch(n);
  std::vector<cl_ulong> b(n);
  std::vector<float> u(n), v(n);
  compute.queue().enqueueReadBuffer(bits, CL_TRUE, 0, n * sizeof(cl_ulong), b.data());
  compute.queue().enqueueReadBuffer(uniform, CL_TRUE, 0, n * sizeof(float), u.data());
  compute.queue().enqueueReadBuffer(keyed, CL_TRUE, 0, n * sizeof(float), v.data());
  double mean = 0, keyed_mean = 0;
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_EQ(b[k], rng_bits(seed, stream, k));
    ASSERT_EQ(u[k], rng_uniform(seed, stream, k));
    ASSERT_EQ(v[k], keyed_uniform(key, static_cast<std::uint32_t>(k)));
    mean += u[k];
    keyed_mean += v[k];
  }
  EXPECT_NEAR(mean / n, 0.5, 0.02);  // 4096 uniforms: standard error 0.0045
  EXPECT_NEAR(keyed_mean / n, 0.5, 0.02);
}

// The keyed numbers of consecutive cells are uncorrelated and evenly spread: lag-1 correlation and
// a chi-square test over 64 bins of 2^16 draws (63 degrees of freedom; 110 is the 0.9999 quantile),
// for a few keys.
TEST(Rng, KeyedNumbersOfNeighbouringCellsAreIndependentAndUniform) {
  for (std::uint64_t pass : {0ULL, 1ULL, 12345ULL}) {
    const std::uint64_t key = rng_key(1, 0x70747273ULL, pass);
    const std::uint32_t n = 1u << 16;
    std::vector<int> bins(64, 0);
    double sum = 0, sum2 = 0, lag = 0, previous = keyed_uniform(key, 0);
    for (std::uint32_t k = 0; k < n; ++k) {
      const double u = keyed_uniform(key, k);
      ++bins[static_cast<int>(u * 64)];
      sum += u;
      sum2 += u * u;
      if (k > 0) lag += (u - 0.5) * (previous - 0.5);
      previous = u;
    }
    const double variance = sum2 / n - (sum / n) * (sum / n);
    EXPECT_NEAR(variance, 1.0 / 12, 0.002) << "pass " << pass;
    EXPECT_LT(std::fabs(lag / (n - 1) / variance), 0.02)
        << "lag-1 correlation, pass " << pass;  // ±4σ
    double chi2 = 0;
    for (int c : bins) chi2 += (c - n / 64.0) * (c - n / 64.0) / (n / 64.0);
    EXPECT_LT(chi2, 110) << "pass " << pass;
  }
}

}  // namespace
}  // namespace runnel
