// SPDX-License-Identifier: MIT
// Helpers shared by the tests: scratch folders, files, and running the runnel binary.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/models/checkpoint.hpp"

namespace runnel {
class SphSolver;
}

namespace runnel::test {

// The device every OpenCL test runs on, created once per test process: the CPU (PoCL), or
// $RUNNEL_TEST_DEVICE.
ComputeContext& compute();
// That device's selector ("cpu", or $RUNNEL_TEST_DEVICE), for a test that needs a context of its
// own.
std::string test_device();
// A second context on the same device whose passes of serial runs (the sort, the step
// statistics) are cut as the other kind of device cuts them: a GPU's cut on the CPU, and back.
ComputeContext& compute_cut_the_other_way();

// A fresh, empty folder for one test, removed when the test ends.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

void write_text(const std::string& path, const std::string& text);
std::string read_text(const std::string& path);

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};
// Runs the runnel binary with `args` (shell-quoted here) and captures its output.
CliResult run_cli(const std::vector<std::string>& args, const std::string& env = "");
// The same for another program (found on PATH), e.g. GDAL's gdalinfo.
CliResult run_program(const std::string& program, const std::vector<std::string>& args,
                      const std::string& env = "");

std::string source_dir();

// A name as a parameterized test's suffix: '-' becomes '_' ("stream-power" → "stream_power").
inline std::string param_name(std::string name) {
  for (char& c : name) c = c == '-' ? '_' : c;
  return name;
}

// Everything a restart needs (heights, steps, clock, fields, counters, particles), compared bit for
// bit.
void expect_same_state(const CheckpointData& a, const CheckpointData& b);

// The number after "KEY": in a JSON text (the first occurrence); -1e300 if the key is absent.
double json_number(const std::string& json, const std::string& key);

// How a device result in integer quanta compares with its double-precision oracle: float and
// double may round a floor() differently, so a vertex may differ by a quantum or a few; a wrong
// algorithm differs by far more, and at most vertices.
struct QuantaComparison {
  std::int64_t worst = 0;    // largest |device − reference|, quanta
  double exact_share = 0;    // share of the vertices that agree exactly
  std::int64_t changed = 0;  // vertices the reference changed at all (the case is not trivial)
};
QuantaComparison compare_quanta(const std::vector<std::int64_t>& device,
                                const std::vector<std::int64_t>& reference,
                                const std::vector<std::int64_t>& before);

// A terrain of independent uniform heights in [0, relief) m on 1 m cells: every cell a pit or a
// peak, so an oracle comparison exercises every neighbour relation of the grid models' kernels.
Heightmap rough_terrain(int nx, int ny, float relief, unsigned seed);

// The mechanical energy of incompressible water, E = Σ m (½|v|² + g y), v the velocities the last
// step ended with (no elastic energy: dfsph's water does not compress).
double incompressible_energy(SphSolver& solver);

}  // namespace runnel::test
