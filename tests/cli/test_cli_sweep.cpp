// SPDX-License-Identifier: MIT
// runnel sweep end to end: the same 2 × 2 × 2 sweep run by one worker, by two, member by member
// (as SLURM array tasks would) and by two MPI ranks gives byte-identical member outputs and the
// same results.csv; a rerun skips done members and redoes interrupted ones; bad sweep files are
// refused before anything runs.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

const char* kBase = R"([run]
steps = 15
[terrain]
generator = "fbm"
size = 33
cell = 2.0
)";

const char* kSweep = R"([sweep]
base = "base.toml"
metrics = ["eroded_volume", "hypsometric_integral", "mass_balance_abs"]
[axes]
model = ["pipe", "olsen"]
"pipe.rain" = [0.01, 0.02]
seed = [1, 2]
)";

std::string member_file(const ScratchDir& dir, const std::string& sweep, int member,
                        const std::string& name) {
  char folder[16];
  std::snprintf(folder, sizeof folder, "%04d", member);
  return dir.path(sweep + "/members/" + folder + "/" + name);
}

TEST(CliSweep, SerialParallelAndMemberByMemberGiveIdenticalResults) {
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), kBase);
  test::write_text(dir.path("sweep.toml"), kSweep);
  const std::string sweep = dir.path("sweep.toml");
  auto r = run_cli({"sweep", sweep, "--out", dir.path("serial"), "-j", "1", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli({"sweep", sweep, "--out", dir.path("parallel"), "-j", "2", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int m = 0; m < 8; ++m) {
    r = run_cli(
        {"sweep", sweep, "--out", dir.path("tasks"), "--member", std::to_string(m), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
  }
  ASSERT_EQ(run_cli({"sweep", sweep, "--out", dir.path("tasks"), "--collect"}).exit_code, 0);
  std::vector<std::string> ways = {"parallel", "tasks"};
  if (RUNNEL_HAVE_MPI && test::run_program("mpirun", {"--version"}).exit_code == 0) {
    // Allowed to run as root and oversubscribed, as in CI.
    r = test::run_program(
        "mpirun", {"--allow-run-as-root", "--oversubscribe", "-np", "2", RUNNEL_BINARY, "sweep",
                   sweep, "--out", dir.path("mpi"), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    ways.push_back("mpi");
  } else {
    // Not a skip of the test (the other three ways ran): say why this way did not.
    std::printf(
        "note: the MPI way did not run: runnel was built without MPI or mpirun is missing\n");
  }

  const std::string results = test::read_text(dir.path("serial/results.csv"));
  EXPECT_EQ(std::count(results.begin(), results.end(), '\n'), 9) << results;
  EXPECT_EQ(
      results.substr(0, results.find('\n')),
      "member,run.model,pipe.rain,run.seed,eroded_volume,hypsometric_integral,mass_balance_abs");
  EXPECT_EQ(test::read_text(dir.path("parallel/results.csv")), results);
  EXPECT_EQ(test::read_text(dir.path("tasks/results.csv")), results);
  for (int m = 0; m < 8; ++m) {
    for (const char* name :
         {"final.npy", "final.tif", "final.asc", "result.csv", "scenario.toml"}) {
      const std::string serial = test::read_text(member_file(dir, "serial", m, name));
      ASSERT_FALSE(serial.empty()) << m << " " << name;
      EXPECT_EQ(test::read_text(member_file(dir, "parallel", m, name)), serial) << m << " " << name;
      EXPECT_EQ(test::read_text(member_file(dir, "tasks", m, name)), serial) << m << " " << name;
    }
  }
  // The pipe members differ with the rain and the seed: the axes reach the runs.
  EXPECT_NE(test::read_text(member_file(dir, "serial", 0, "final.npy")),
            test::read_text(member_file(dir, "serial", 2, "final.npy")));
  const std::string manifest = test::read_text(dir.path("serial/manifest.csv"));
  EXPECT_EQ(std::count(manifest.begin(), manifest.end(), '\n'), 9);
  EXPECT_EQ(manifest.find("pending"), std::string::npos) << manifest;

  // A rerun skips the done members; an interrupted one (no result row) is redone alone, the same.
  const std::string before = test::read_text(member_file(dir, "serial", 5, "final.npy"));
  std::filesystem::remove(member_file(dir, "serial", 5, "result.csv"));
  std::filesystem::remove(member_file(dir, "serial", 5, "final.npy"));
  r = run_cli({"sweep", sweep, "--out", dir.path("serial"), "-j", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("7 done already"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("member 5 done"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_text(member_file(dir, "serial", 5, "final.npy")), before);
  EXPECT_EQ(test::read_text(dir.path("serial/results.csv")), results);

  // Another sweep in the same folder is refused, with nothing started.
  std::string changed = kSweep;
  changed.replace(changed.find("[1, 2]"), 6, "[1, 3]");
  test::write_text(dir.path("changed.toml"), changed);
  r = run_cli({"sweep", dir.path("changed.toml"), "--out", dir.path("serial")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holds another sweep"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  // The SLURM array script runs one member per task.
  r = run_cli(
      {"sweep", sweep, "--out", dir.path("serial"), "--slurm-script", "--time", "02:00:00"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = test::read_text(dir.path("serial/sweep.slurm"));
  EXPECT_NE(script.find("#SBATCH --array=0-7"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --time=02:00:00"), std::string::npos) << script;
  EXPECT_NE(script.find("--member \"$SLURM_ARRAY_TASK_ID\""), std::string::npos) << script;
}

// The SPH solver is an axis like any other key: each member runs the solver its row names, and a
// member repeats itself bit for bit whether the sweep runs serially or in parallel.
TEST(CliSweep, SweepsTheSphSolverAndEveryMemberRepeatsItself) {
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), R"([run]
model = "sph"
sim_time = 3
[terrain]
generator = "fbm"
size = 33
cell = 2.0
[rain]
intensity = 60000.0
)");
  test::write_text(dir.path("sweep.toml"), R"([sweep]
base = "base.toml"
metrics = ["eroded_volume", "mass_balance_abs"]
[axes]
"sph.solver" = ["wcsph", "dfsph"]
)");
  for (const char* way : {"serial", "parallel"}) {
    const auto r = run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path(way), "-j",
                            way == std::string("serial") ? "1" : "2", "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << way << ": " << r.err;
  }
  const std::string results = test::read_text(dir.path("serial/results.csv"));
  EXPECT_EQ(results.substr(0, results.find('\n')),
            "member,sph.solver,eroded_volume,mass_balance_abs");
  EXPECT_NE(results.find("\n0,wcsph,"), std::string::npos) << results;
  EXPECT_NE(results.find("\n1,dfsph,"), std::string::npos) << results;
  EXPECT_EQ(test::read_text(dir.path("parallel/results.csv")), results);
  for (int m = 0; m < 2; ++m) {
    const std::string serial = test::read_text(member_file(dir, "serial", m, "final.npy"));
    ASSERT_FALSE(serial.empty()) << m;
    EXPECT_EQ(test::read_text(member_file(dir, "parallel", m, "final.npy")), serial) << m;
  }
  EXPECT_NE(test::read_text(member_file(dir, "serial", 0, "final.npy")),
            test::read_text(member_file(dir, "serial", 1, "final.npy")))
      << "the two solvers move the bed differently";
  const std::string dfsph = test::read_text(member_file(dir, "serial", 1, "metrics.json"));
  EXPECT_NE(dfsph.find("\"solver\": \"dfsph\""), std::string::npos) << dfsph;
}

// With checkpoint_every, an interrupted member goes on from its newest checkpoint, and ends as the
// uninterrupted member did, bit for bit (what a SLURM requeue after the time limit relies on).
TEST(CliSweep, AnInterruptedMemberResumesFromItsNewestCheckpoint) {
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), kBase);  // 15 steps
  test::write_text(dir.path("sweep.toml"), R"([sweep]
base = "base.toml"
checkpoint_every = 5
[axes]
model = ["pipe", "sph"]
)");
  const std::string sweep = dir.path("sweep.toml");
  ASSERT_EQ(run_cli({"sweep", sweep, "--out", dir.path("s"), "-j", "1", "--quiet"}).exit_code, 0);
  for (int m = 0; m < 2; ++m) {
    // The member "was killed" after its checkpoint at step 10: no step 15, no outputs, no result
    // row.
    for (const char* gone :
         {"checkpoints/step_00000015.h5", "final.npy", "result.csv", "metrics.json"})
      std::filesystem::remove(member_file(dir, "s", m, gone));
    ASSERT_TRUE(std::filesystem::exists(member_file(dir, "s", m, "checkpoints/step_00000010.h5")));
  }
  const auto r = run_cli({"sweep", sweep, "--out", dir.path("s"), "-j", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("0 done already"), std::string::npos) << r.err;
  // The same sweep, never interrupted.
  ASSERT_EQ(run_cli({"sweep", sweep, "--out", dir.path("whole"), "-j", "1", "--quiet"}).exit_code,
            0);
  for (int m = 0; m < 2; ++m) {
    EXPECT_EQ(test::json_number(test::read_text(member_file(dir, "s", m, "metrics.json")),
                                "resumed_from_step"),
              10)
        << m;
    EXPECT_EQ(test::read_text(member_file(dir, "s", m, "final.npy")),
              test::read_text(member_file(dir, "whole", m, "final.npy")))
        << m;
    EXPECT_EQ(test::read_text(member_file(dir, "s", m, "result.csv")),
              test::read_text(member_file(dir, "whole", m, "result.csv")))
        << m;
  }
}

// A member whose run fails (a collapsing time step) is reported as failed with its message, the
// others finish, the sweep exits 1; a rerun retries only the failed one.
TEST(CliSweep, AFailedMemberIsListedWithItsMessage) {
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), kBase);
  test::write_text(dir.path("sweep.toml"), R"([sweep]
base = "base.toml"
[axes]
model = ["pipe"]
"pipe.dt_min" = [1e-9, 0.5]
"pipe.rain" = [50.0]
)");
  auto r = run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("s"), "-j", "2", "--quiet"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("1 members failed"), std::string::npos) << r.err;
  const std::string manifest = test::read_text(dir.path("s/manifest.csv"));
  EXPECT_NE(manifest.find("0,pipe,1e-09,50,done,"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("1,pipe,0.5,50,failed,"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("time step collapsed"), std::string::npos) << manifest;
  const std::string results = test::read_text(dir.path("s/results.csv"));
  EXPECT_EQ(std::count(results.begin(), results.end(), '\n'), 2)
      << "header and the done member: " << results;
  r = run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("s"), "-j", "1"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("1 done already"), std::string::npos) << r.err;
}

TEST(CliSweep, CollectsSphWaterResolutionAndLeavesItEmptyForOtherModels) {
  // A sweep over the storm's intensity can say which members resolve their water: the lighter
  // storm's water on the bed is all films (footprints holding fewer than 8 other particles' water,
  // docs/erosion.md "Films"), the heavier one's mostly not. The pipe model has no particles, so its
  // fields stay empty and the columns stay aligned.
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), R"([run]
sim_time = 10
[terrain]
generator = "fbm"
size = 33
cell = 2.0
[rain]
lifespan = 1e9
[erosion]
morphological_factor = 100.0
)");
  test::write_text(dir.path("sweep.toml"), R"([sweep]
base = "base.toml"
metrics = ["film_share", "eroded_volume", "median_particles_per_footprint"]
[axes]
model = ["sph", "pipe"]
"rain.intensity" = [2000.0, 60000.0]
)");
  const auto r =
      run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("s"), "-j", "1", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string results = test::read_text(dir.path("s/results.csv"));
  std::istringstream lines(results);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(
      line,
      "member,run.model,rain.intensity,film_share,eroded_volume,median_particles_per_footprint");
  std::map<std::string, std::vector<std::string>> rows;  // "model intensity" -> the three metrics
  while (std::getline(lines, line)) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    if (!line.empty() && line.back() == ',') f.push_back("");
    ASSERT_EQ(f.size(), 6u) << line;
    rows[f[1] + " " + f[2]] = {f[3], f[4], f[5]};
  }
  ASSERT_EQ(rows.size(), 4u) << results;
  const double light = std::stod(rows["sph 2000"][0]), heavy = std::stod(rows["sph 60000"][0]);
  EXPECT_GT(light, 0.9) << results;
  EXPECT_LT(heavy, 0.5) << results;
  EXPECT_GT(std::stod(rows["sph 60000"][2]), std::stod(rows["sph 2000"][2])) << results;
  for (const char* pipe : {"pipe 2000", "pipe 60000"}) {
    EXPECT_EQ(rows[pipe][0], "") << results;
    EXPECT_FALSE(rows[pipe][1].empty()) << results;
    EXPECT_EQ(rows[pipe][2], "") << results;
  }
}

// One coordinating sweep a folder at a time; a member another process is running now is left to it;
// and a member resumes only its own checkpoint, never another run's placed in its folder.
TEST(CliSweep, TwoSweepsNeverShareAFolderOrAMember) {
  ScratchDir dir;
  test::write_text(dir.path("base.toml"), kBase);
  test::write_text(dir.path("sweep.toml"), R"([sweep]
base = "base.toml"
checkpoint_every = 5
[axes]
model = ["pipe", "olsen"]
)");
  const std::string sweep = dir.path("sweep.toml"), out = dir.path("s");
  // Claim the folder (the SLURM script is written once the folder is the sweep's).
  ASSERT_EQ(run_cli({"sweep", sweep, "--out", out, "--slurm-script"}).exit_code, 0);
  auto hold = [](const std::string& lock) {
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
    EXPECT_GE(fd, 0);
    EXPECT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    return fd;
  };
  // Another sweep coordinating in the folder (its lock held here, as a running sweep holds it).
  int fd = hold(out + "/.runnel-sweep.lock");
  auto r = run_cli({"sweep", sweep, "--out", out, "-j", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("another runnel sweep is running"), std::string::npos) << r.err;
  ::close(fd);
  // Member 1 running in another process (its run lock held): skipped, not failed.
  std::filesystem::create_directories(member_file(dir, "s", 1, ""));
  fd = hold(member_file(dir, "s", 1, ".runnel.lock"));
  r = run_cli({"sweep", sweep, "--out", out, "-j", "1"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("member 1 is being run by another process; skipped"), std::string::npos)
      << r.err;
  EXPECT_TRUE(std::filesystem::exists(member_file(dir, "s", 0, "result.csv")));
  EXPECT_FALSE(std::filesystem::exists(member_file(dir, "s", 1, "result.csv")));
  ::close(fd);
  // Member 0's checkpoint placed in member 1's folder: refused, the member listed as failed.
  std::filesystem::create_directories(member_file(dir, "s", 1, "checkpoints"));
  std::filesystem::copy_file(member_file(dir, "s", 0, "checkpoints/step_00000010.h5"),
                             member_file(dir, "s", 1, "checkpoints/step_00000010.h5"));
  r = run_cli({"sweep", sweep, "--out", out, "-j", "1"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(member_file(dir, "s", 1, "result.csv")));
  EXPECT_NE(test::read_text(dir.path("s/manifest.csv")).find("the checkpoint of another run"),
            std::string::npos)
      << test::read_text(dir.path("s/manifest.csv"));
}

TEST(CliSweep, BadSweepFilesAreRefusedBeforeAnythingRuns) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[axes]\n\"pipe.nonsense\" = [1, 2]\n", "unknown parameter"},
      {"[axes]\n\"pipe.rain\" = []\n", "no values"},
      {"[sweep]\nmax_members = 3\n[axes]\n\"pipe.rain\" = [0.01, 0.02, 0.03, 0.04]\n", "--force"},
      {"[axes]\nterrain = [\"missing.asc\"]\n", "no such file"},
      {"[sweep]\nmetrics = [\"nope\"]\n[axes]\nseed = [1]\n", "unknown metric"},
      {"[sweep]\ncombine = \"zip\"\n[axes]\nseed = [1, 2]\nmodel = [\"pipe\"]\n", "one length"},
      {"[sweep]\nspeed = 3\n[axes]\nseed = [1]\n", "unknown key"},
      {"[axes]\n\"pipe.rain\" = [-1]\n", "pipe.rain"},
      {"[sweep]\n", "[axes]"},
      {"[axes]\nseed = 5\n", "an axis is a list of values ([5])"},
      {"[axes]\nmodel = [\"pipe\"]\n\"run.model\" = [\"olsen\"]\n", "both vary run.model"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string file = dir.path("bad" + std::to_string(k) + ".toml");
    test::write_text(file, cases[k].first);
    const std::string out = dir.path("out" + std::to_string(k));
    const auto r = run_cli({"sweep", file, "--out", out});
    EXPECT_EQ(r.exit_code, 2) << cases[k].first << r.err;
    EXPECT_NE(r.err.find(cases[k].second), std::string::npos) << cases[k].first << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing started: " << cases[k].first;
  }
}

}  // namespace
}  // namespace runnel
