// SPDX-License-Identifier: MIT
#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "runnel/sph/sph_solver.hpp"

namespace runnel::test {

ScratchDir::ScratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scratch";
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  root_ = std::filesystem::temp_directory_path() /
          ("runnel-test-" + std::to_string(getpid()) + "-" + name);
  std::filesystem::remove_all(root_);
  std::filesystem::create_directories(root_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(root_, ec);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

CliResult run_cli(const std::vector<std::string>& args, const std::string& env) {
  return run_program(RUNNEL_BINARY, args, env);
}

CliResult run_program(const std::string& program, const std::vector<std::string>& args,
                      const std::string& env) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(getpid()) + "-" + std::to_string(std::random_device{}());
  const std::string out_path = (dir / ("runnel-cli-out-" + tag)).string();
  const std::string err_path = (dir / ("runnel-cli-err-" + tag)).string();
  std::string cmd = env.empty() ? "" : env + " ";
  cmd += shell_quote(program);
  for (auto& a : args) cmd.append(" ").append(shell_quote(a));
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  cmd.append(" </dev/null >").append(out_path).append(" 2>").append(err_path);
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out_path);
  r.err = read_text(err_path);
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return r;
}

std::string source_dir() {
  return RUNNEL_SOURCE_DIR;
}

}  // namespace runnel::test

namespace runnel::test {

// RUNNEL_TEST_DEVICE runs the OpenCL tests on another device (scripts/gpu-check.sh: the GPU).
std::string test_device() {
  const char* device = std::getenv("RUNNEL_TEST_DEVICE");
  return device ? device : "cpu";
}

// The test process's contexts are never destroyed: one released by the exit handlers, after the
// OpenCL implementation's own statics have gone, corrupts the heap of some (Oclgrind's).
ComputeContext& compute() {
  static ComputeContext& context = *new ComputeContext(test_device());
  return context;
}

ComputeContext& compute_cut_the_other_way() {
  static ComputeContext& context = *new ComputeContext(test_device());
  static const bool flipped = (context.set_wide(!context.wide()), true);
  (void)flipped;
  return context;
}

double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return -1e300;
  return std::stod(json.substr(at + key.size() + 4));
}

QuantaComparison compare_quanta(const std::vector<std::int64_t>& device,
                                const std::vector<std::int64_t>& reference,
                                const std::vector<std::int64_t>& before) {
  QuantaComparison c;
  std::size_t exact = 0;
  for (std::size_t k = 0; k < device.size(); ++k) {
    const std::int64_t d =
        device[k] > reference[k] ? device[k] - reference[k] : reference[k] - device[k];
    c.worst = std::max(c.worst, d);
    exact += d == 0;
    c.changed += reference[k] != before[k];
  }
  c.exact_share = device.empty() ? 0.0 : static_cast<double>(exact) / device.size();
  return c;
}

Heightmap rough_terrain(int nx, int ny, float relief, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> height(0.0f, relief);
  Heightmap rough(nx, ny, 1.0);
  for (float& h : rough.h) h = height(rng);
  return rough;
}

void expect_same_state(const CheckpointData& a, const CheckpointData& b) {
  EXPECT_EQ(a.height_fixed, b.height_fixed);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t k = 0; k < a.fields.size(); ++k) {
    EXPECT_EQ(a.fields[k].name, b.fields[k].name);
    EXPECT_EQ(a.fields[k].f32, b.fields[k].f32) << a.fields[k].name;
    EXPECT_EQ(a.fields[k].i64, b.fields[k].i64) << a.fields[k].name;
  }
  EXPECT_EQ(a.model_counters, b.model_counters);
  EXPECT_EQ(a.particles.id, b.particles.id);
  for (int f = 0; f < kPersistentFieldCount; ++f) EXPECT_EQ(a.particles.f[f], b.particles.f[f]);
  EXPECT_EQ(a.particles.sediment, b.particles.sediment);
}

double incompressible_energy(SphSolver& solver) {
  const SphSettings& s = solver.settings();
  const HostParticles p = solver.particles().download();
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v2 = double(p.f[kVx][i]) * p.f[kVx][i] + double(p.f[kVy][i]) * p.f[kVy][i] +
                      double(p.f[kVz][i]) * p.f[kVz][i];
    e += s.mass() * (0.5 * v2 + s.gravity * p.f[kY][i]);
  }
  return e;
}

}  // namespace runnel::test
