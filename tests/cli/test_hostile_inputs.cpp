// SPDX-License-Identifier: MIT
// Hostile and absurd inputs: each gets exit 2 and one line naming the thing and the
// problem, with nothing written; bytes from the file are echoed escaped.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cstdint>
#include <fstream>

#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

// Exit 2, one line, containing every fragment, and no terminal control byte.
void expect_refused(const test::CliResult& r, const std::vector<std::string>& fragments,
                    const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << what;
  for (const auto& f : fragments)
    EXPECT_NE(r.err.find(f), std::string::npos) << what << ": " << r.err;
}

const std::string kHeader = "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n";

TEST(HostileInputs, BadFlagValuesAreRefusedNotIgnored) {
  ScratchDir dir;
  expect_refused(run_cli({"run", "--steps", "-3", "--out", dir.path("a")}), {"--steps", "-3"},
                 "--steps -3");
  expect_refused(run_cli({"run", "--sim-time", "-1", "--out", dir.path("a")}), {"--sim-time"},
                 "--sim-time -1");
  expect_refused(run_cli({"run", "--sim-time", "nan", "--out", dir.path("a")}), {"--sim-time"},
                 "--sim-time nan");
  expect_refused(run_cli({"run", "--seed", "-5", "--out", dir.path("a")}), {"--seed"}, "--seed");
  EXPECT_FALSE(std::filesystem::exists(dir.path("a"))) << "nothing written";
  expect_refused(run_cli({"validate", "dambreak", "--resolution", "0"}), {"--resolution"},
                 "validate --resolution 0");
  expect_refused(run_cli({"generate", "fbm", "--cell", "1e300", "-o", dir.path("t.asc")}),
                 {"--cell", "1e300"}, "generate --cell 1e300");
  EXPECT_FALSE(std::filesystem::exists(dir.path("t.asc")));
  expect_refused(run_cli({"bench", "sph", "--tile", "-1"}), {"--tile"}, "bench --tile -1");
  expect_refused(
      run_cli({"generate", "fbm", "--size", "9", "--range", "0:1", "-o", dir.path("t.npy")}),
      {"--range"}, "generate --range for npy");
  // CLI11's own wording ("not in range 0.000000 to 1797…") is gone.
  const auto r = run_cli({"run", "--keep-checkpoints", "0", "--out", dir.path("a")});
  expect_refused(r, {"--keep-checkpoints", "from 1 to"}, "--keep-checkpoints 0");
  EXPECT_EQ(r.err.find("1797"), std::string::npos) << r.err;
}

// A value the command would ignore is refused: an empty path or name, a flag given a value, an
// option the case does not take, a parameter the case does not read.
TEST(HostileInputs, ValuesACommandWouldIgnoreAreRefused) {
  ScratchDir dir;
  const std::string out = dir.path("a");
  for (const char* flag : {"--terrain", "--generate", "--device", "--trace"})
    expect_refused(run_cli({"run", flag, "", "--steps", "1", "--out", out}), {flag, "empty"},
                   std::string(flag) + " ''");
  expect_refused(run_cli({"export", dir.path("none.h5"), "--range", "", "-o", dir.path("x.png")}),
                 {"--range", "empty"}, "export --range ''");
  expect_refused(run_cli({"run", "--generate", "plane", "--overwrite=2", "--out", out}),
                 {"overwrite"}, "--overwrite=2");
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written";
  expect_refused(run_cli({"validate", "dambreak", "--set", "run.steps=5"}),
                 {"run.steps", "validate dambreak", "sph.*"}, "validate dambreak --set run.*");
  expect_refused(run_cli({"bench", "sph", "--set", "pipe.rain=1"}), {"pipe.rain", "bench sph"},
                 "bench sph --set pipe.*");
  expect_refused(run_cli({"validate", "mobile-bed", "--settle", "5", "--out", dir.path("mb")}),
                 {"--settle"}, "validate mobile-bed --settle");
  EXPECT_FALSE(std::filesystem::exists(dir.path("mb"))) << "--out not created";
  expect_refused(run_cli({"validate", "stream-power", "--set", "sph.cfl=0.1"}), {"--set"},
                 "validate stream-power --set");
  expect_refused(
      run_cli({"run", "--generate", "fbm", "--set", "terrain.set.octaves=2.5", "--out", out}),
      {"octaves", "whole number"}, "a fractional octave count");
  // What the cases do read is still taken.
  EXPECT_EQ(run_cli({"run", "--generate", "plane", "--overwrite=true", "--steps", "1", "--quiet",
                     "--out", out})
                .exit_code,
            0);
}

// Echoed text is cut: a name a megabyte long gives a line of at most a few kilobytes.
TEST(HostileInputs, EchoedTextIsBounded) {
  ScratchDir dir;
  const std::string name(1 << 20, 'g');
  test::write_text(dir.path("s.toml"), "[terrain]\ngenerator = \"plane\"\n[[probes]]\nname = \"" +
                                           name + "\"\nx = 1\ny = 1\n[[probes]]\nname = \"" + name +
                                           "\"\nx = 2\ny = 2\n");
  const auto probes = run_cli({"run", dir.path("s.toml"), "--steps", "1", "--out", dir.path("o")});
  expect_refused(probes, {"probes[2].name", "already defined"}, "a 1 MB probe name");
  EXPECT_LT(probes.err.size(), 2500u);
  // (An argument may hold 128 KiB at most.)
  const auto path = run_cli(
      {"run", "--terrain", dir.path(std::string(100000, 'p') + ".asc"), "--out", dir.path("o")});
  expect_refused(path, {"more bytes"}, "a 100 kB terrain path");
  EXPECT_LT(path.err.size(), 2500u);
}

TEST(HostileInputs, NonFiniteAndAbsurdNumbersInTerrainFiles) {
  ScratchDir dir;
  const std::pair<const char*, std::string> files[] = {
      {"huge.asc", kHeader + "1 2 3\n4 5e38 6\n7 8 9\n"},
      {"cell_inf.asc",
       "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1e300\n1 2 3 4 5 6 7 8 9\n"},
      {"cell_tiny.asc",
       "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1e-300\n1 2 3 4 5 6 7 8 9\n"},
      {"origin_nan.asc",
       "ncols 3\nnrows 3\nxllcorner nan\nyllcorner 0\ncellsize 1\n1 2 3 4 5 6 7 8 9\n"},
      {"twice.asc",
       "ncols 3\nnrows 3\nncols 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3 4 5 6 7 8 9\n"},
      {"mixed.asc", "ncols 3\nnrows 3\nxllcenter 0\nyllcorner 0\ncellsize 1\n1 2 3 4 5 6 7 8 9\n"},
      {"wide.asc",
       "ncols 99999999999999999999999\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\n"},
  };
  for (const auto& [name, text] : files) {
    test::write_text(dir.path(name), text);
    const auto r = run_cli({"convert", dir.path(name), dir.path("out.npy")});
    expect_refused(r, {name}, name);
    EXPECT_EQ(r.err.find("-9223372036854775808"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("out.npy"))) << name;
  }
}

TEST(HostileInputs, HeightRangesBeyondAnyTerrainAreRefused) {
  ScratchDir dir;
  ASSERT_EQ(run_cli({"generate", "fbm", "--size", "9", "-o", dir.path("in.png")}).exit_code, 0);
  expect_refused(
      run_cli({"convert", dir.path("in.png"), dir.path("out.asc"), "--range", "-1e300:1e300"}),
      {"in.png", "range"}, "PNG read range ±1e300");
  EXPECT_FALSE(std::filesystem::exists(dir.path("out.asc")));
  expect_refused(run_cli({"convert", dir.path("in.png"), dir.path("out.png"), "--range", "0:1e39"}),
                 {"range"}, "--range 0:1e39");
  EXPECT_FALSE(std::filesystem::exists(dir.path("out.png")));
}

TEST(HostileInputs, EchoedBytesAreEscaped) {
  ScratchDir dir;
  test::write_text(dir.path("escape.asc"), kHeader + "1 2 3\n4 \x1b[2J\x1b[31mred 6\n7 8 9\n");
  const auto r = run_cli({"convert", dir.path("escape.asc"), dir.path("out.npy")});
  expect_refused(r, {"escape.asc", "\\x1b[2J"}, "escape sequence");
}

// A minimal .npy file with `header` as its dictionary.
void write_npy(const std::string& path, const std::string& dict, std::size_t data_bytes) {
  std::string header = dict;
  while ((10 + header.size() + 1) % 64) header += ' ';
  header += '\n';
  std::ofstream f(path, std::ios::binary);
  f.write("\x93NUMPY\x01\x00", 8);
  const std::uint16_t len = static_cast<std::uint16_t>(header.size());
  f.write(reinterpret_cast<const char*>(&len), 2);
  f << header << std::string(data_bytes, '\0');
}

TEST(HostileInputs, NpyHeadersAreParsedStrictly) {
  ScratchDir dir;
  const std::pair<const char*, std::string> cases[] = {
      {"negative", "{'descr': '<f4', 'fortran_order': False, 'shape': (-17, -19), }"},
      {"nested", "{'descr': '<f4', 'fortran_order': False, 'shape': ((3, 3), 3), }"},
      {"unterminated", "{'descr': '<f4', 'fortran_order': False, 'shape': (3, 3), "},
      {"object", "{'descr': '|O', 'fortran_order': False, 'shape': (3, 3), }"},
      {"unicode", "{'descr': '<U2', 'fortran_order': False, 'shape': (3, 3), }"},
      {"structured", "{'descr': [('a', '<f4')], 'fortran_order': False, 'shape': (3, 3), }"},
  };
  for (const auto& [name, dict] : cases) {
    const std::string file = dir.path(std::string(name) + ".npy");
    write_npy(file, dict, 36);
    expect_refused(run_cli({"info", file}), {name}, name);
  }
  // The dtype is named as it is, not reported missing.
  expect_refused(run_cli({"info", dir.path("object.npy")}), {"'|O'", "not float32"}, "|O");
  expect_refused(run_cli({"info", dir.path("structured.npy")}), {"structured"}, "structured");
}

TEST(HostileInputs, OutputEqualToInputIsRefused) {
  ScratchDir dir;
  ASSERT_EQ(run_cli({"generate", "fbm", "--size", "9", "-o", dir.path("in.png")}).exit_code, 0);
  const std::string before = test::read_text(dir.path("in.png"));
  expect_refused(run_cli({"convert", dir.path("in.png"), dir.path("in.png"), "--range", "0:10"}),
                 {"in.png", "input"}, "same file");
  expect_refused(run_cli({"convert", dir.path("in.png"), dir.path("./in.png")}), {"input"},
                 "same file by another name");
  EXPECT_EQ(test::read_text(dir.path("in.png")), before);
}

// An n x n ESRI grid of `height`, with `corner` at (0, 0).
std::string flat_asc(int n, const std::string& height, const std::string& corner) {
  std::string s = "ncols " + std::to_string(n) + "\nnrows " + std::to_string(n) +
                  "\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  for (int k = 0; k < n * n; ++k) s += (k == 0 ? corner : height) + (k % n == n - 1 ? "\n" : " ");
  return s;
}

TEST(HostileInputs, FixedPointOverflowIsRefusedUpFront) {
  ScratchDir dir;
  test::write_text(dir.path("tall.asc"), flat_asc(16, "1e6", "1e6"));
  expect_refused(run_cli({"run", "--terrain", dir.path("tall.asc"), "--steps", "1", "--set",
                          "erosion.height_quantum=1e-12", "--out", dir.path("o")}),
                 {"erosion.height_quantum"}, "1e6 m at 1e-12 m quanta");
  test::write_text(dir.path("huge.asc"), flat_asc(16, "1", "1e13"));
  expect_refused(
      run_cli({"run", "--terrain", dir.path("huge.asc"), "--steps", "1", "--out", dir.path("o")}),
      {"huge.asc"}, "1e13 m");
  EXPECT_FALSE(std::filesystem::exists(dir.path("o")));
}

TEST(HostileInputs, TerrainsTooSmallForTheSphModelAreRefusedWithTheSmallestSize) {
  ScratchDir dir;
  for (const char* size : {"2", "3", "9"}) {
    expect_refused(
        run_cli({"run", "--generate", "plane", "--set", std::string("terrain.size=") + size,
                 "--steps", "5", "--out", dir.path("o")}),
        {"too small", "at least 16 x 16"}, size);
  }
  // The grid models run on the smallest terrain there is.
  EXPECT_EQ(run_cli({"run", "--generate", "plane", "--model", "pipe", "--set", "terrain.size=2",
                     "--steps", "5", "--quiet", "--out", dir.path("p")})
                .exit_code,
            0);
}

// An error found after the first launches: with an empty kernel cache PoCL (the suite's device)
// compiles a kernel for its first launch in a worker thread, and the process used to exit under
// that compile, a segmentation fault (exit 139) in about half the runs instead of exit 2 and the
// error's line. Several runs, each with a cache of its own.
TEST(HostileInputs, AnErrorWhileAKernelStillCompilesExitsWithItsLine) {
  for (int run = 0; run < 4; ++run) {
    ScratchDir dir;
    const auto r =
        run_cli({"run", "--generate", "plane", "--steps", "1", "--out", dir.path("o"), "--set",
                 "terrain.size=33", "--set", "rain.region=\"disc\"", "--set", "rain.disc_x=500",
                 "--set", "rain.disc_z=500", "--set", "rain.disc_radius=5"},
                "POCL_CACHE_DIR=" + dir.path("kernels"));
    expect_refused(r, {"rain.disc", "off the terrain"},
                   "a cold kernel cache, run " + std::to_string(run));
  }
}

TEST(HostileInputs, ScenarioContradictionsAreRefusedWithTheirKeys) {
  ScratchDir dir;
  const std::vector<std::string> base = {"run", "--generate", "plane",      "--steps",
                                         "1",   "--out",      dir.path("o")};
  auto with = [&](std::vector<std::string> sets) {
    std::vector<std::string> args = base;
    for (auto& s : sets) args.insert(args.end(), {"--set", s});
    return run_cli(args);
  };
  expect_refused(with({"terrain.size=33", "rain.region=\"disc\"", "rain.disc_x=500",
                       "rain.disc_z=500", "rain.disc_radius=5"}),
                 {"rain.disc", "off the terrain"}, "disc off the terrain");
  expect_refused(with({"sph.density_min=1", "sph.density_max=1"}), {"sph.density_min"},
                 "density_min = density_max");
  expect_refused(with({"terrain.size=33", "rain.spawn_height=1e6"}), {"rain.spawn_height"},
                 "spawn height 1e6");
  expect_refused(
      with({"terrain.size=33", "erosion.model=\"acidity\"", "erosion.exchange_interval=0.01"}),
      {"erosion.exchange_interval", "stream-power model only"},
      "an exchange interval for the per-contact acidity model");
  EXPECT_FALSE(std::filesystem::exists(dir.path("o")));
  // 10^8 particles (the key's largest value) need more than 1.5 · 10^8 · 128 bytes (with the
  // store's growth margin): beyond a CPU's share or most GPUs, refused with the figures. A device
  // with more memory (an H200: 150 GB) rightly runs them.
  if (1.5e8 * 128 > static_cast<double>(test::compute().info().global_memory)) {
    expect_refused(with({"terrain.size=33", "rain.max_particles=100000000"}),
                   {"rain.max_particles", "MB of device memory"},
                   "a particle budget beyond the device");
  } else {
    std::printf("note: rain.max_particles 1e8 not checked: this device has %.0f MB\n",
                static_cast<double>(test::compute().info().global_memory) / 1e6);
  }
  // 10^8 droplets (the key's largest value) on the plane's 257 x 257 vertices: a batch moves in
  // lockstep, and at one droplet for two vertices they dig the pits they gather in without bound
  // until the balance breaks. Refused at once, whatever the device (it ran 4 minutes and broke the
  // balance by 10^12 m^3 before); one for 4 vertices runs and balances exactly.
  expect_refused(run_cli({"run", "--generate", "plane", "--model", "droplet", "--steps", "1",
                          "--set", "droplet.batch=100000000", "--out", dir.path("o")}),
                 {"droplet.batch", "66049 vertices", "one for 4"}, "droplet.batch 1e8");
  expect_refused(run_cli({"run", "--generate", "fbm", "--model", "droplet", "--steps", "1", "--set",
                          "droplet.batch=40000", "--out", dir.path("o")}),
                 {"droplet.batch"}, "droplet.batch of 0.6 a vertex");
  EXPECT_FALSE(std::filesystem::exists(dir.path("o")));
  const auto quarter = run_cli({"run", "--generate", "fbm", "--model", "droplet", "--steps", "3",
                                "--set", "droplet.batch=16512", "--quiet", "--out", dir.path("q")});
  EXPECT_EQ(quarter.exit_code, 0) << quarter.err;
  EXPECT_EQ(test::json_number(test::read_text(dir.path("q/metrics.json")), "mass_balance_abs"), 0);
}

}  // namespace
}  // namespace runnel
