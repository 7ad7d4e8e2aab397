// SPDX-License-Identifier: MIT
// Checkpoints end to end: rolling checkpoints, the series, resume, info, export, Python (h5py).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <type_traits>

#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

const std::vector<std::string> kSmallRun = {"--generate",      "fbm",   "--set",
                                            "terrain.size=49", "--set", "rain.rate=3000",
                                            "--seed",          "4",     "--quiet"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(CliCheckpoint, RollingCheckpointsSeriesAndExactResume) {
  ScratchDir dir;
  auto r = run_cli(with({"run", "--steps", "200", "--out", dir.path("full")}, kSmallRun));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli(with({"run", "--steps", "100", "--out", dir.path("half"), "--checkpoint-every", "20",
                    "--keep-checkpoints", "2", "--series-every", "25"},
                   kSmallRun));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The newest two checkpoints are kept.
  std::vector<std::string> kept;
  for (auto& e : std::filesystem::directory_iterator(dir.path("half/checkpoints")))
    kept.push_back(e.path().filename());
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<std::string>{"step_00000080.h5", "step_00000100.h5"}));
  // Five frames in the series: the start (step 0) and steps 25, 50, 75 and 100.
  const H5File series = H5File::open_read(dir.path("half/series.h5"));
  EXPECT_EQ(series.dims("/height"), (std::vector<hsize_t>{5, 49, 49}));
  EXPECT_EQ(series.read_int64("/height_step", {5}),
            (std::vector<std::int64_t>{0, 25, 50, 75, 100}));
  // Resuming the checkpoint of step 100 for 100 steps ends where the uninterrupted run ended.
  r = run_cli({"resume", dir.path("half/checkpoints/step_00000100.h5"), "--steps", "100", "--out",
               dir.path("resumed"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_text(dir.path("full/final.npy")),
            test::read_text(dir.path("resumed/final.npy")));
  const std::string metrics = test::read_text(dir.path("resumed/metrics.json"));
  EXPECT_NE(metrics.find("\"resumed_from_step\": 100"), std::string::npos);
}

// A run that stops as unstable keeps its work: its last good state (here the rolling checkpoint of
// step 250, before the failing step) as failed.h5, its gauges' readings, and a metrics.json that
// says where and why it stopped; resumed with a changed parameter, it goes on from there.
TEST(CliCheckpoint, ARunStoppedAsUnstableKeepsItsLastGoodStateAndResumesWithOtherParameters) {
  ScratchDir dir;
  test::write_text(dir.path("s.toml"),
                   "[terrain]\ngenerator = \"fbm\"\n[run]\nprobe_every = 0.5\n"
                   "[[probes]]\nname = \"g\"\nx = 60\ny = 60\n");
  // dfsph with a sane range it leaves after a few hundred steps of the storm.
  const auto r =
      run_cli({"run", dir.path("s.toml"), "--sim-time", "20", "--set", "sph.solver=dfsph", "--set",
               "sph.density_max=1.001", "--checkpoint-every", "50", "--series-every", "100",
               "--quiet", "--out", dir.path("o")});
  ASSERT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("unstable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(dir.path("o/failed.h5")), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("o/final.h5")));
  const std::string metrics = test::read_text(dir.path("o/metrics.json"));
  EXPECT_NE(metrics.find("\"stopped\""), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("sph.density_min/max"), std::string::npos) << metrics;
  const CheckpointData good = read_checkpoint(dir.path("o/failed.h5"));
  ASSERT_GT(good.steps, 0u);
  EXPECT_EQ(good.steps % 50, 0u);
  EXPECT_NE(metrics.find("\"last_good_step\": " + std::to_string(good.steps)), std::string::npos)
      << metrics;
  // The series' frames up to the failure, under the final name (no partial file left).
  EXPECT_FALSE(std::filesystem::exists(dir.path("o/series.h5.partial")));
  const std::vector<std::int64_t> frames =
      H5File::open_read(dir.path("o/series.h5")).read_int64("/height_step");
  EXPECT_EQ(frames, (std::vector<std::int64_t>{0, 100, 200})) << "a frame every 100 steps to 262";
  // The gauge's readings up to the failure, one row per half second from 0.
  const std::string probes = test::read_text(dir.path("o/probes.csv"));
  EXPECT_GE(std::count(probes.begin(), probes.end(), '\n'), 1 + static_cast<long>(good.time / 0.5))
      << probes;

  // The same state goes on with a sane range: 20 more steps from the last good one.
  const auto resumed = run_cli({"resume", dir.path("o/failed.h5"), "--steps", "20", "--set",
                                "sph.density_max=1.5", "--quiet", "--out", dir.path("resumed")});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const CheckpointData after = read_checkpoint(dir.path("resumed/final.h5"));
  EXPECT_EQ(after.steps, good.steps + 20);
  EXPECT_NE(after.parameters_toml.find("density_max = 1.5"), std::string::npos);
  // The terrain and the model are the checkpoint's: changing them is refused.
  EXPECT_EQ(run_cli({"resume", dir.path("o/failed.h5"), "--steps", "1", "--set", "terrain.cell=3",
                     "--out", dir.path("x")})
                .exit_code,
            2);
  EXPECT_FALSE(std::filesystem::exists(dir.path("x")));
}

// Overwrites a whole dataset of doubles or int64 in an HDF5 file, as an editor of the file would.
template <class T>
void overwrite_dataset(const std::string& file, const std::string& name, const std::vector<T>& v) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  EXPECT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Dclose(d);
  H5Fclose(f);
}

// An edited or damaged series is refused by the NetCDF export, not written as it is: a grid that
// is not a regular raster, a time that is not a number, frames out of order or repeated (which
// also bounds the work: one frame listed 300,000 times is not expanded), and no frames at all.
TEST(CliCheckpoint, TheNetcdfExportRefusesASeriesItCannotTrust) {
  ScratchDir dir;
  ASSERT_EQ(run_cli(with({"run", "--steps", "6", "--series-every", "2", "--model", "pipe", "--out",
                          dir.path("o")},
                         kSmallRun))
                .exit_code,
            0);
  const std::string good = dir.path("o/series.h5");
  ASSERT_EQ(run_cli({"export", good, "--format", "netcdf", "-o", dir.path("good.nc")}).exit_code,
            0);
  const H5File series = H5File::open_read(good);
  const std::vector<hsize_t> grid = series.dims("/grid/x");
  const std::vector<std::int64_t> steps = series.read_int64("/height_step");
  const std::vector<double> times = series.read_double("/height_time", {steps.size()});
  ASSERT_EQ(steps.size(), 4u);
  struct Edit {
    std::string what, expected;
    std::function<void(const std::string&)> apply;
  };
  const std::vector<Edit> edits = {
      {"x all 0", "/grid/x does not rise",
       [&](const std::string& f) {
         overwrite_dataset(f, "/grid/x", std::vector<double>(grid[0] * grid[1], 0.0));
       }},
      {"a NaN time", "has the time nan",
       [&](const std::string& f) {
         std::vector<double> t = times;
         t[2] = NAN;
         overwrite_dataset(f, "/height_time", t);
       }},
      {"a repeated frame", "does not come after",
       [&](const std::string& f) {
         overwrite_dataset(f, "/height_step", std::vector<std::int64_t>(steps.size(), steps[1]));
       }},
  };
  for (const Edit& e : edits) {
    const std::string edited = dir.path("edited.h5");
    std::filesystem::copy_file(good, edited, std::filesystem::copy_options::overwrite_existing);
    e.apply(edited);
    const auto r = run_cli({"export", edited, "--format", "netcdf", "-o", dir.path("e.nc")});
    EXPECT_EQ(r.exit_code, 2) << e.what << ": " << r.err;
    EXPECT_NE(r.err.find(e.expected), std::string::npos) << e.what << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("e.nc"))) << e.what;
  }
  // A series of particles only has no terrain frame to export.
  ASSERT_EQ(run_cli({"run", "--steps", "2", "--particles-every", "1", "--generate", "plane",
                     "--set", "terrain.size=33", "--quiet", "--out", dir.path("p")})
                .exit_code,
            0);
  const auto none =
      run_cli({"export", dir.path("p/series.h5"), "--format", "netcdf", "-o", dir.path("p.nc")});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("no terrain frames"), std::string::npos) << none.err;
}

TEST(CliCheckpoint, AResumedRunExchangesOnTheUninterruptedRunsClock) {
  // With an erosion exchange interval the bed exchanges only at the steps that cross a multiple of
  // it: the schedule follows from the clock alone, so a resume from a step between two exchanges
  // (steps of about 1.9 ms here, two an interval) ends where the uninterrupted run ended.
  ScratchDir dir;
  std::vector<std::string> run = kSmallRun;
  run.insert(run.end(), {"--set", "erosion.exchange_interval=0.004"});
  auto r = run_cli(with({"run", "--steps", "150", "--out", dir.path("full")}, run));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli(
      with({"run", "--steps", "75", "--out", dir.path("half"), "--checkpoint-every", "75"}, run));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli({"resume", dir.path("half/checkpoints/step_00000075.h5"), "--steps", "75", "--out",
               dir.path("resumed"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_text(dir.path("full/final.npy")),
            test::read_text(dir.path("resumed/final.npy")));
  EXPECT_NE(test::read_text(dir.path("full/final.npy")),
            test::read_text(dir.path("half/final.npy")))
      << "the second half changed the terrain";
}

TEST(CliCheckpoint, InfoAndExportEveryFormat) {
  ScratchDir dir;
  ASSERT_EQ(run_cli(with({"run", "--steps", "50", "--out", dir.path("run")}, kSmallRun)).exit_code,
            0);
  const std::string h5 = dir.path("run/final.h5");
  auto r = run_cli({"info", h5, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"steps\": 50"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"schema_version\": 3"), std::string::npos);
  r = run_cli({"info", h5});
  EXPECT_NE(r.out.find("runnel checkpoint"), std::string::npos);
  const Heightmap reference = read_terrain(dir.path("run/final.npy"));
  for (const char* format : {"asc", "png", "npy"}) {
    const std::string out = dir.path(std::string("t.") + format);
    r = run_cli({"export", h5, "--format", format, "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Heightmap t = read_terrain(out);
    EXPECT_EQ(t.nx, 49);
    EXPECT_NEAR(t.max_height(), reference.max_height(), 1e-3) << format;
  }
  r = run_cli({"export", h5, "--format", "obj", "-o", dir.path("t.obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string obj = test::read_text(dir.path("t.obj"));
  EXPECT_EQ(std::count(obj.begin(), obj.end(), 'v') > 0, true);
  std::size_t vertices = 0, faces = 0;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    vertices += line.rfind("v ", 0) == 0;
    faces += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(vertices, 49u * 49u);
  EXPECT_EQ(faces, 2u * 48u * 48u);
  r = run_cli({"export", h5, "--format", "png", "-o", dir.path("wrong.asc")});
  EXPECT_EQ(r.exit_code, 2);
}

TEST(CliCheckpoint, BadCheckpointsExitWithTwoAndOneLine) {
  ScratchDir dir;
  test::write_text(dir.path("junk.h5"), "not hdf5 at all");
  for (std::vector<std::string> args : std::vector<std::vector<std::string>>{
           {"resume", dir.path("junk.h5"), "--steps", "5", "--out", dir.path("o")},
           {"resume", dir.path("none.h5"), "--steps", "5", "--out", dir.path("o")},
           {"info", dir.path("junk.h5")},
           {"export", dir.path("junk.h5"), "--format", "asc", "-o", dir.path("x.asc")}}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path("o")));
  EXPECT_FALSE(std::filesystem::exists(dir.path("x.asc")));
}

TEST(CliCheckpoint, PythonReadsTheCheckpointWithH5py) {
  if (std::system("/usr/bin/python3 -c 'import h5py, numpy' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  }
  ScratchDir dir;
  ASSERT_EQ(run_cli(with({"run", "--steps", "40", "--out", dir.path("run")}, kSmallRun)).exit_code,
            0);
  const std::string cmd = "/usr/bin/python3 " + test::source_dir() +
                          "/docs/python/read_checkpoint.py " + dir.path("run/final.h5") + " > " +
                          dir.path("py.txt") + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.path("py.txt"));
  const std::string out = test::read_text(dir.path("py.txt"));
  EXPECT_NE(out.find("terrain 49 x 49"), std::string::npos) << out;
  EXPECT_NE(out.find("step 40"), std::string::npos) << out;
  // A grid model's checkpoint: its fields, with their shapes.
  ASSERT_EQ(run_cli(with({"run", "--model", "pipe", "--steps", "20", "--out", dir.path("pipe")},
                         kSmallRun))
                .exit_code,
            0);
  const std::string pipe_cmd = "/usr/bin/python3 " + test::source_dir() +
                               "/docs/python/read_checkpoint.py " + dir.path("pipe/final.h5") +
                               " > " + dir.path("pipe.txt") + " 2>&1";
  ASSERT_EQ(std::system(pipe_cmd.c_str()), 0) << test::read_text(dir.path("pipe.txt"));
  const std::string pipe = test::read_text(dir.path("pipe.txt"));
  EXPECT_NE(pipe.find("model pipe"), std::string::npos) << pipe;
  EXPECT_NE(pipe.find("field surface_water__outflux: shape (49, 49, 4)"), std::string::npos)
      << pipe;
}

}  // namespace
}  // namespace runnel
