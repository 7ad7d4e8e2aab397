// SPDX-License-Identifier: MIT
// What used to crash, hang, destroy an input or run unasked: nested TOML keys, huge NPY headers,
// special files, outputs that are inputs, a busy or foreign output folder, unverifiable
// checkpoints, integers beyond their range, write errors on stdout and file-size limits, shell
// metacharacters in sweep.slurm, sweeps too large to expand, rain held back by its budget.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "test_support.hpp"

namespace runnel {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::run_program;
using test::ScratchDir;

// Any command that would block on a FIFO is stopped here instead of hanging the suite; 124 is
// timeout's exit code, so a hang fails the exit-code check.
const std::string kGuard = "timeout 120";

void expect_exit(const test::CliResult& r, int code, const std::string& fragment,
                 const std::string& what) {
  EXPECT_EQ(r.exit_code, code) << what << ": " << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << what << ": " << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << what;
}

std::string deep_key(int segments) {
  std::string key = "a";
  for (int k = 1; k < segments; ++k) key += ".a";
  return key;
}

TEST(ResourceLimits, TomlKeysNestedPastTheLimitAreRefusedNotACrash) {
  ScratchDir dir;
  // 300,000 segments overflowed the TOML library's stack (SIGSEGV).
  const std::string deep = deep_key(300000) + " = 1\n";
  test::write_text(dir.path("deep.toml"), deep);
  expect_exit(run_cli({"run", dir.path("deep.toml"), "--out", dir.path("o")}), 2,
              "nested deeper than 64", "scenario");
  std::string header = "[";
  header.append(deep_key(300000)).append("]\nx = 1\n");
  test::write_text(dir.path("header.toml"), header);
  expect_exit(run_cli({"run", dir.path("header.toml"), "--out", dir.path("o")}), 2,
              "nested deeper than 64", "table header");
  test::write_text(dir.path("sweep.toml"), deep);
  expect_exit(run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("s")}), 2,
              "nested deeper than 64", "sweep file");
  test::write_text(dir.path("graph.toml"), deep);
  expect_exit(run_cli({"generate", "--graph", dir.path("graph.toml"), "-o", dir.path("t.asc")}), 2,
              "nested deeper than 64", "terrain graph");
  EXPECT_FALSE(fs::exists(dir.path("o")) || fs::exists(dir.path("t.asc")));
  // What the limit leaves: dots inside strings, values and comments are not key segments.
  test::write_text(dir.path("fine.toml"),
                   "# a.b.c.d.e.f.g.h.i.j.k.l.m.n.o.p.q.r.s.t.u.v.w.x.y.z\n[terrain]\n"
                   "generator = \"plane\"\nsize = 17\ncell = 1.5\n[run]\nsteps = 1\n");
  EXPECT_EQ(run_cli({"run", dir.path("fine.toml"), "--quiet", "--out", dir.path("f")}).exit_code,
            0);
}

TEST(ResourceLimits, NpyHeadersLongerThanNumpyReadsAreRefused) {
  ScratchDir dir;
  for (std::size_t pad : {20000u, 200000u}) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (32, 32), }";
    header += std::string(pad, ' ') + "\n";
    std::string file = "\x93NUMPY\x02";
    file += '\0';
    const auto n = static_cast<std::uint32_t>(header.size());
    for (int b = 0; b < 4; ++b) file += static_cast<char>((n >> (8 * b)) & 0xff);
    file += header + std::string(32 * 32 * 4, '\0');
    test::write_text(dir.path("big.npy"), file);
    expect_exit(run_cli({"convert", dir.path("big.npy"), dir.path("out.asc")}), 2,
                "NumPy itself reads", "header of " + std::to_string(pad));
  }
}

TEST(ResourceLimits, SpecialFilesAsInputsAreRefusedAtOnce) {
  ScratchDir dir;
  ASSERT_EQ(mkfifo(dir.path("fifo.asc").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo(dir.path("fifo.toml").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo(dir.path("fifo.h5").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir.path("zero.asc"));
  ASSERT_EQ(run_cli({"generate", "plane", "--size", "17", "-o", dir.path("t.asc")}).exit_code, 0);
  const std::string out = dir.path("o");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"run", "--terrain", dir.path("fifo.asc"), "--out", out}, "FIFO"},
      {{"run", "--terrain", dir.path("zero.asc"), "--out", out}, "character device"},
      {{"run", dir.path("fifo.toml"), "--out", out}, "FIFO"},
      {{"run", "--terrain", dir.path("t.asc"), "--model", "pipe", "--set",
        "ground.rain_mask=" + dir.path("fifo.asc"), "--out", out},
       "FIFO"},
      {{"sweep", dir.path("fifo.toml"), "--out", out}, "FIFO"},
      {{"generate", "--graph", dir.path("fifo.toml"), "-o", dir.path("g.asc")}, "FIFO"},
      {{"resume", dir.path("fifo.h5"), "--steps", "1", "--out", out}, "FIFO"},
      {{"info", dir.path("fifo.asc")}, "FIFO"},
  };
  for (const auto& [args, kind] : cases) {
    std::string command;
    for (const std::string& a : args) command.append(a).append(" ");
    expect_exit(run_cli(args, kGuard), 2, kind, command);
  }
}

TEST(ResourceLimits, NoOutputReplacesAnInputADeviceOrAnotherOutput) {
  ScratchDir dir;
  ASSERT_EQ(run_cli({"generate", "fbm", "--size", "17", "-o", dir.path("t.asc")}).exit_code, 0);
  const std::string terrain = test::read_text(dir.path("t.asc"));
  const std::vector<std::string> run = {
      "run", "--terrain", dir.path("t.asc"), "--model", "thermal", "--steps", "2", "--quiet"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = run;
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  // --trace naming the terrain truncated it before the run.
  expect_exit(with({"--trace", dir.path("t.asc"), "--out", dir.path("o")}), 2, "terrain.file",
              "--trace over the terrain");
  // The terrain inside --out under an output's name ("./" spelled differently, too).
  ASSERT_EQ(with({"--out", dir.path("o")}).exit_code, 0);
  fs::copy_file(dir.path("t.asc"), dir.path("o/final.asc"), fs::copy_options::overwrite_existing);
  const std::string inside = test::read_text(dir.path("o/final.asc"));
  std::vector<std::string> in_out = run;
  in_out[2] = dir.path("o/./final.asc");
  in_out.insert(in_out.end(), {"--out", dir.path("o")});
  expect_exit(run_cli(in_out), 2, "terrain.file", "terrain inside --out");
  EXPECT_EQ(test::read_text(dir.path("o/final.asc")), inside);
  expect_exit(with({"--trace", dir.path("o/final.npy"), "--out", dir.path("o")}), 2, "--trace",
              "--trace over an output");
  expect_exit(run_cli({"generate", "fbm", "--size", "17", "-o", dir.path("x.png"), "--picture",
                       dir.path("x.png")}),
              2, "--picture", "generate -o X --picture X");
  EXPECT_FALSE(fs::exists(dir.path("x.png")));
  // Device nodes and FIFOs are never replaced by a rename.
  ASSERT_EQ(mkfifo(dir.path("pipe.asc").c_str(), 0600), 0);
  expect_exit(run_cli({"generate", "fbm", "--size", "17", "-o", dir.path("pipe.asc")}, kGuard), 2,
              "FIFO", "generate into a FIFO");
  EXPECT_TRUE(fs::is_fifo(dir.path("pipe.asc")));
  fs::create_symlink("/dev/null", dir.path("null.asc"));
  expect_exit(run_cli({"convert", dir.path("t.asc"), dir.path("null.asc")}), 2, "character device",
              "convert onto a device");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(test::read_text(dir.path("t.asc")), terrain) << "the input is untouched";
}

TEST(ResourceLimits, AFolderHoldsOneRunAtATime) {
  ScratchDir dir;
  const std::vector<std::string> run = {
      "run",     "--generate", "plane", "--set",   "terrain.size=17", "--model",
      "thermal", "--steps",    "2",     "--quiet", "--out",           dir.path("o")};
  ASSERT_EQ(run_cli(run).exit_code, 0);
  // Another run's pictures and series are not left beside a new run's outputs.
  std::vector<std::string> other = run;
  other.insert(other.end(), {"--set", "thermal.talus_angle=30"});
  ASSERT_EQ(run_cli({"run", "--generate", "plane", "--set", "terrain.size=17", "--model", "thermal",
                     "--steps", "4", "--series-every", "2", "--quiet", "--out", dir.path("o")})
                .exit_code,
            0)
      << "the same run, longer, may write into its own folder";
  ASSERT_TRUE(fs::exists(dir.path("o/series.h5")));
  test::write_text(dir.path("o/notes.txt"), "the user's own file");
  expect_exit(run_cli(other), 2, "another run", "another run into the folder");
  other.push_back("--overwrite");
  ASSERT_EQ(run_cli(other).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir.path("o/series.h5"))) << "the earlier run's series went";
  EXPECT_TRUE(fs::exists(dir.path("o/notes.txt"))) << "files runnel did not write stay";
  // While a run holds the folder, another is refused (the lock is held here, as a run holds it).
  const int fd = ::open(dir.path("o/.runnel.lock").c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  expect_exit(run_cli(other), 2, "another runnel run is writing", "a locked folder");
  ::close(fd);
  EXPECT_EQ(run_cli(other).exit_code, 0) << "the folder is free again";
  // A folder that cannot take files is refused before the first step.
  expect_exit(run_cli({"run", "--generate", "plane", "--set", "terrain.size=17", "--steps",
                       "1000000", "--out", "/proc/self"}),
              2, "/proc/self", "an unwritable folder");
}

TEST(ResourceLimits, ACheckpointWithoutItsDigestIsNotResumed) {
  ScratchDir dir;
  ASSERT_EQ(run_cli({"run", "--generate", "plane", "--set", "terrain.size=17", "--model", "thermal",
                     "--steps", "2", "--quiet", "--out", dir.path("o")})
                .exit_code,
            0);
  fs::copy_file(dir.path("o/final.h5"), dir.path("plain.h5"));
  const hid_t file = H5Fopen(dir.path("plain.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  ASSERT_GE(H5Adelete(file, "digest"), 0);
  H5Fclose(file);
  EXPECT_EQ(
      run_cli({"resume", dir.path("o/final.h5"), "--steps", "1", "--quiet", "--out", dir.path("r")})
          .exit_code,
      0);
  expect_exit(run_cli({"resume", dir.path("plain.h5"), "--steps", "1", "--out", dir.path("r2")}), 2,
              "no digest", "resume");
  expect_exit(run_cli({"info", dir.path("plain.h5")}), 2, "no digest", "info");
}

TEST(ResourceLimits, IntegerFlagsBeyondTheirRangeAreRefusedNotClamped) {
  ScratchDir dir;
  expect_exit(run_cli({"resume", "x.h5", "--steps", "99999999999999999999999"}), 2, "--steps",
              "resume --steps 1e23");
  expect_exit(run_cli({"run", "--steps", "9223372036854775808", "--out", dir.path("o")}), 2,
              "--steps", "run --steps 2^63");
  expect_exit(run_cli({"run", "--seed", "1e30", "--out", dir.path("o")}), 2, "--seed",
              "run --seed 1e30");
  expect_exit(run_cli({"run", "--checkpoint-every", "2.5", "--out", dir.path("o")}), 2,
              "--checkpoint-every", "a fraction");
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

TEST(ResourceLimits, WriteErrorsAndFileSizeLimitsAreErrorsNotSignals) {
  ScratchDir dir;
  const std::string runnel = RUNNEL_BINARY;
  const auto full = run_program("sh", {"-c", "'" + runnel + "' params > /dev/full"});
  EXPECT_EQ(full.exit_code, 1) << full.err;
  EXPECT_NE(full.err.find("standard output"), std::string::npos) << full.err;
  // A file-size limit of 10 KB: the writer fails with exit 1 (not killed by SIGXFSZ), and no
  // partial file stands under the final name.
  const auto limited =
      run_program("sh", {"-c", "ulimit -f 10; '" + runnel + "' generate fbm --size 257 -o '" +
                                   dir.path("big.asc") + "'"});
  EXPECT_EQ(limited.exit_code, 1) << limited.err;
  EXPECT_NE(limited.err.find("big.asc"), std::string::npos) << limited.err;
  EXPECT_FALSE(fs::exists(dir.path("big.asc")));
}

TEST(ResourceLimits, SweepSlurmScriptsQuoteEveryNameAndValue) {
  ScratchDir dir;
  test::write_text(dir.path("sweep.toml"),
                   "[axes]\n\"run.model\" = [\"thermal\"]\n"
                   "\"terrain.size\" = [17]\n\"run.iterations\" = [2]\n");
  // A folder named to run a command if it were pasted unquoted into a shell.
  const std::string folder = dir.path("a $(touch PWNED) 'quoted' `touch PWNED2`");
  const auto r = run_cli({"sweep", dir.path("sweep.toml"), "--out", folder, "--slurm-script"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = folder + "/sweep.slurm";
  ASSERT_TRUE(fs::exists(script));
  EXPECT_EQ(run_program("bash", {"-n", script}).exit_code, 0) << test::read_text(script);
  // Run it as SLURM would run array task 0: the member runs, and nothing in the name executes.
  const auto task =
      run_program("bash", {script}, "cd '" + dir.root().string() + "' && SLURM_ARRAY_TASK_ID=0");
  EXPECT_EQ(task.exit_code, 0) << task.err << test::read_text(script);
  EXPECT_TRUE(fs::exists(folder + "/members/0000/metrics.json")) << "member 0 ran";
  EXPECT_FALSE(fs::exists(dir.path("PWNED")) || fs::exists(dir.path("PWNED2")) ||
               fs::exists("PWNED") || fs::exists("PWNED2"));
  // What sbatch cannot carry on an #SBATCH line is refused before anything is written.
  expect_exit(run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("line\nbreak"),
                       "--slurm-script"}),
              2, "#SBATCH", "a newline in the folder");
  EXPECT_FALSE(fs::exists(dir.path("line\nbreak")));
  expect_exit(run_cli({"sweep", dir.path("sweep.toml"), "--out", dir.path("t"), "--slurm-script",
                       "--time", "1:00; touch PWNED"}),
              2, "--time", "a time with a command");
}

TEST(ResourceLimits, ASweepTooLargeIsRefusedBeforeItIsExpanded) {
  ScratchDir dir;
  // Seven axes of ten values: 10^7 members, gigabytes of parameter sets once expanded.
  std::string text = "[axes]\n\"run.model\" = [\"thermal\"]\n";
  const char* keys[] = {"thermal.talus_angle", "thermal.rate", "terrain.seed",  "run.seed",
                        "terrain.size",        "terrain.cell", "run.iterations"};
  const char* values[] = {
      "[10,11,12,13,14,15,16,17,18,19]", "[0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]",
      "[1,2,3,4,5,6,7,8,9,10]",          "[1,2,3,4,5,6,7,8,9,10]",
      "[17,18,19,20,21,22,23,24,25,26]", "[1,2,3,4,5,6,7,8,9,10]",
      "[1,2,3,4,5,6,7,8,9,10]"};
  for (int a = 0; a < 7; ++a)
    text.append("\"").append(keys[a]).append("\" = ").append(values[a]).append("\n");
  test::write_text(dir.path("huge.toml"), text);
  expect_exit(run_cli({"sweep", dir.path("huge.toml"), "--out", dir.path("s")}), 2, "max_members",
              "10^7 members");
  expect_exit(run_cli({"sweep", dir.path("huge.toml"), "--out", dir.path("s"), "--force"}), 2,
              "split the sweep", "10^7 members with --force");
  EXPECT_FALSE(fs::exists(dir.path("s")));
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

TEST(ResourceLimits, RainHeldBackByItsBudgetIsCountedAndCautionedAbout) {
  ScratchDir dir;
  ASSERT_EQ(test::run_cli({"generate", "plane", "--size", "17", "-o", dir.path("t.asc")}).exit_code,
            0);
  const std::vector<std::string> storm = {"run",
                                          "--terrain",
                                          dir.path("t.asc"),
                                          "--sim-time",
                                          "1",
                                          "--set",
                                          "rain.intensity=60000",
                                          "--set",
                                          "rain.lifespan=5"};
  auto run = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = storm;
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"--quiet", "--out", dir.path(out)});
    return test::run_cli(args);
  };
  const auto capped = run("capped", {"--set", "rain.max_particles=20"});
  ASSERT_EQ(capped.exit_code, 0) << capped.err;
  EXPECT_NE(capped.err.find("held back"), std::string::npos) << capped.err;
  EXPECT_NE(capped.err.find("rain.max_particles = 20 "), std::string::npos) << capped.err;
  const std::string m = test::read_text(dir.path("capped/metrics.json"));
  const double held = test::json_number(m, "particles_held_back");
  const double spawned = test::json_number(m, "particles_spawned");
  EXPECT_GT(held, 0.0);
  EXPECT_LE(spawned, 20.0 + 1e-9 + test::json_number(m, "particles_outflow") +
                         test::json_number(m, "particles_evaporated"));
  // Requested = delivered + held back, in particle volumes (spacing 0.5 m on 1 m cells).
  const double volume = 0.125;
  EXPECT_NEAR(test::json_number(m, "rain_requested_volume"), (spawned + held) * volume, 1e-9);
  EXPECT_NEAR(test::json_number(m, "rain_delivered_volume"), spawned * volume, 1e-9);
  EXPECT_NEAR(test::json_number(m, "rain_volume"), spawned * volume, 1e-9);

  // The default budget follows the storm: nothing held back, and room for every drop that can
  // be alive at once (the rate times the longest lifespan).
  const auto free = run("free", {});
  ASSERT_EQ(free.exit_code, 0) << free.err;
  EXPECT_EQ(free.err.find("held back"), std::string::npos) << free.err;
  const std::string f = test::read_text(dir.path("free/metrics.json"));
  EXPECT_EQ(test::json_number(f, "particles_held_back"), 0.0);
  EXPECT_GE(test::json_number(f, "max_particles"),
            test::json_number(f, "rate_particles_per_s") * 5.0 * 1.25);
}

TEST(ResourceLimits, ATerrainTheSpacingCannotResolveGetsACautionNamingTheFix) {
  ScratchDir dir;
  ASSERT_EQ(test::run_cli({"generate", "fbm", "--size", "17", "-o", dir.path("t.asc")}).exit_code,
            0);
  // 60 mm/h on 16 m x 16 m in drops of 0.125 m³: 7 drops a minute.
  const auto sparse = test::run_cli({"run", "--terrain", dir.path("t.asc"), "--steps", "5", "--set",
                                     "rain.intensity=60", "--quiet", "--out", dir.path("sparse")});
  ASSERT_EQ(sparse.exit_code, 0) << sparse.err;
  EXPECT_NE(sparse.err.find("drops a minute"), std::string::npos) << sparse.err;
  EXPECT_NE(sparse.err.find("set sph.spacing to"), std::string::npos) << sparse.err;
  // Particles of 4 m on hills of a metre or two.
  const auto coarse = test::run_cli({"run", "--terrain", dir.path("t.asc"), "--steps", "5", "--set",
                                     "sph.spacing=4", "--set", "rain.rate=100", "--quiet", "--out",
                                     dir.path("coarse")});
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  EXPECT_NE(coarse.err.find("relief"), std::string::npos) << coarse.err;
  // The default storm on the same hills says nothing of the kind.
  const auto fine = test::run_cli({"run", "--terrain", dir.path("t.asc"), "--steps", "5", "--quiet",
                                   "--out", dir.path("fine")});
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_EQ(fine.err.find("sph.spacing to"), std::string::npos) << fine.err;
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

TEST(ResourceLimits, EveryMessageIsOneLineWithoutTerminalControls) {
  test::ScratchDir dir;
  // Escape sequences and newlines in a --set key, a file name, a scenario's text and an --out path:
  // each message is one line with the bytes written as \xNN.
  // A TOML key spelled with an escape: the parser turns \u001b into the byte itself.
  test::write_text(dir.path("esc.toml"), "[terrain]\n\"\\u001b]0;owned\\u0007\" = 1\n");
  const std::vector<std::vector<std::string>> cases = {
      {"run", "--set", "\x1b[2Jkey=1", "--out", dir.path("o")},
      {"run", "--terrain", dir.path("a\nb\x1b[31m.asc"), "--out", dir.path("o")},
      {"run", dir.path("esc.toml"), "--out", dir.path("o")},
      {"convert", dir.path("x\r\x1b[1A.asc"), dir.path("y.asc")},
  };
  for (const auto& args : cases) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("\\x1b"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// AddressSanitizer, as GCC and clang announce it.
#if defined(__SANITIZE_ADDRESS__)
#define RUNNEL_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RUNNEL_TEST_ASAN 1
#endif
#endif

// Under an address-space limit (`ulimit -v`, as batch systems set it) a model too large for what
// the limit leaves is refused with the sizes, before PoCL aborts inside an allocation. (Not under
// AddressSanitizer, which needs the whole address space for its shadow memory.)
TEST(ResourceLimits, AnAddressSpaceLimitIsHonouredBeforeAllocating) {
#if defined(RUNNEL_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
#else
  test::ScratchDir dir;
  const auto r =
      test::run_cli({"run", "--generate", "plane", "--set", "terrain.size=4097", "--model",
                     "thermal", "--steps", "1", "--quiet", "--out", dir.path("o")},
                    "ulimit -v 1048576;");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("ulimit -v"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("needs about"), std::string::npos) << r.err;
#endif
}

}  // namespace
}  // namespace runnel
