// SPDX-License-Identifier: MIT
// Outputs survive what a long run meets: a full disk stops the run with exit 1 and one
// line naming the file, no crash and no partial file under a final name; a reused --out never mixes
// two runs; the exit-code rule holds for every writer.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

namespace fs = std::filesystem;

// A tmpfs of `kib` KiB mounted on a fresh folder, unmounted at the end; mounted() is false where
// the test may not mount (not root, or no mount namespace).
class SmallDisk {
 public:
  explicit SmallDisk(const ScratchDir& dir, int kib) : path_(dir.path("disk")) {
    fs::create_directories(path_);
    const std::string cmd =
        "mount -t tmpfs -o size=" + std::to_string(kib) + "k tmpfs '" + path_ + "' 2>/dev/null";
    mounted_ = std::system(cmd.c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) std::system(("umount '" + path_ + "'").c_str());
  }
  bool mounted() const { return mounted_; }
  std::string path(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
  bool mounted_ = false;
};

TEST(OutputSafety, AFullDiskStopsTheRunWithExitOneAndNoPartialFile) {
  ScratchDir dir;
  SmallDisk disk(dir, 200);
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a small tmpfs here (needs root and mount)";
  const auto checkpoints =
      run_cli({"run", "--generate", "fbm", "--set", "terrain.size=65", "--steps", "30",
               "--checkpoint-every", "10", "--quiet", "--out", disk.path("a")});
  EXPECT_EQ(checkpoints.exit_code, 1) << checkpoints.err;
  EXPECT_EQ(std::count(checkpoints.err.begin(), checkpoints.err.end(), '\n'), 1) << checkpoints.err;
  EXPECT_NE(checkpoints.err.find("step_"), std::string::npos) << checkpoints.err;
  EXPECT_EQ(checkpoints.err.find(".tmp"), std::string::npos) << "names the file, not the temporary";
  EXPECT_TRUE(fs::exists(disk.path("a/checkpoints/step_00000010.h5")))
      << "the earlier checkpoints are intact";
  for (auto& e : fs::directory_iterator(disk.path("a/checkpoints")))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  fs::remove_all(disk.path("a"));
  const auto series = run_cli({"run", "--generate", "fbm", "--set", "terrain.size=129", "--steps",
                               "60", "--series-every", "2", "--quiet", "--out", disk.path("b")});
  EXPECT_EQ(series.exit_code, 1) << series.err;
  EXPECT_NE(series.err.find("series"), std::string::npos)
      << series.err;  // series.h5 or series_vtk/
  EXPECT_FALSE(fs::exists(disk.path("b/series.h5"))) << "no partial series under its final name";
  EXPECT_FALSE(fs::exists(disk.path("b/series.h5.partial"))) << "nor left beside it";
}

TEST(OutputSafety, AReusedOutFolderNeverMixesTwoRuns) {
  ScratchDir dir;
  const std::vector<std::string> first = {
      "run",     "--generate",         "plane", "--set", "terrain.size=17", "--steps", "40",
      "--quiet", "--checkpoint-every", "20",    "--out", dir.path("o")};
  ASSERT_EQ(run_cli(first).exit_code, 0);
  ASSERT_TRUE(fs::exists(dir.path("o/checkpoints/step_00000040.h5")));
  // Another run (another seed) with the same --out is refused before it writes anything.
  std::vector<std::string> second = {"run",   "--generate",      "plane",
                                     "--set", "terrain.size=17", "--steps",
                                     "40",    "--quiet",         "--checkpoint-every",
                                     "10",    "--seed",          "9",
                                     "--out", dir.path("o")};
  const auto refused = run_cli(second);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("another run"), std::string::npos) << refused.err;
  EXPECT_TRUE(fs::exists(dir.path("o/checkpoints/step_00000040.h5")));
  // With --overwrite the old run's checkpoints go, and rotation keeps this run's newest three.
  second.push_back("--overwrite");
  ASSERT_EQ(run_cli(second).exit_code, 0);
  std::vector<std::string> names;
  for (auto& e : fs::directory_iterator(dir.path("o/checkpoints")))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"step_00000020.h5", "step_00000030.h5", "step_00000040.h5"}));
  // The same run again (same parameters) may write into its own folder.
  EXPECT_EQ(run_cli(second).exit_code, 0);
}

TEST(OutputSafety, StaleTemporariesOfAKilledWriterAreCleaned) {
  ScratchDir dir;
  fs::create_directories(dir.path("o/checkpoints"));
  test::write_text(dir.path("o/checkpoints/.step_00000010.h5.tmpAbC123"), "half a file");
  ASSERT_EQ(run_cli({"run", "--generate", "plane", "--set", "terrain.size=17", "--steps", "10",
                     "--quiet", "--checkpoint-every", "10", "--out", dir.path("o")})
                .exit_code,
            0);
  EXPECT_FALSE(fs::exists(dir.path("o/checkpoints/.step_00000010.h5.tmpAbC123")));
}

TEST(OutputSafety, AnOutputPathThatCannotBeWrittenIsExitTwoForEveryWriter) {
  ScratchDir dir;
  test::write_text(dir.path("file"), "a file, not a folder");
  ASSERT_EQ(run_cli({"generate", "fbm", "--size", "9", "-o", dir.path("t.asc")}).exit_code, 0);
  ASSERT_EQ(run_cli({"run", "--generate", "plane", "--set", "terrain.size=17", "--steps", "2",
                     "--quiet", "--out", dir.path("o")})
                .exit_code,
            0);
  const std::string bad = dir.path("file/out");
  const std::vector<std::vector<std::string>> writers = {
      {"generate", "fbm", "--size", "9", "-o", bad + ".asc"},
      {"convert", dir.path("t.asc"), bad + ".npy"},
      {"export", dir.path("o/final.h5"), "--format", "asc", "-o", bad + ".asc"},
      {"run", "--generate", "plane", "--set", "terrain.size=17", "--steps", "2", "--out", bad},
      {"resume", dir.path("o/final.h5"), "--steps", "1", "--out", bad},
  };
  for (const auto& args : writers) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("file/out"), std::string::npos) << args[0] << ": " << r.err;
  }
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// A command refused for one of its outputs, or once its case is under way, writes none of them
// and leaves no folder it created.
TEST(OutputSafety, ARefusedCommandWritesNothing) {
  test::ScratchDir dir;
  const auto g = test::run_cli({"generate", "fbm", "--size", "9", "--cell", "1", "-o",
                                dir.path("t.asc"), "--picture", dir.path("nodir/p.png")});
  EXPECT_EQ(g.exit_code, 2) << g.err;
  EXPECT_NE(g.err.find("nodir"), std::string::npos) << g.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("t.asc"))) << "the terrain was written first";
  const auto v =
      test::run_cli({"validate", "hydrostatic", "--resolution", "2000", "--out", dir.path("v")});
  EXPECT_EQ(v.exit_code, 2) << v.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("v"))) << "--out was left behind";
  // An --out that was there before stays.
  std::filesystem::create_directories(dir.path("mine"));
  test::write_text(dir.path("mine/notes.txt"), "kept");
  EXPECT_EQ(
      test::run_cli({"validate", "hydrostatic", "--resolution", "2000", "--out", dir.path("mine")})
          .exit_code,
      2);
  EXPECT_EQ(test::read_text(dir.path("mine/notes.txt")), "kept");
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// --overwrite replaces only what a runnel run wrote into the folder: a user's own file of an
// output's name in a folder runnel never wrote into stays (and the run is refused), and nothing
// is removed or written through a checkpoints/ link into another run's folder.
TEST(OutputSafety, OverwriteRemovesOnlyWhatARunWroteAndNeverThroughALink) {
  test::ScratchDir dir;
  std::filesystem::create_directories(dir.path("mine"));
  test::write_text(dir.path("mine/probes.csv"), "my own gauges\n");
  const std::vector<std::string> run = {"run", "--generate", "plane",      "--steps",
                                        "1",   "--quiet",    "--overwrite"};
  auto with_out = [&](const std::string& out) {
    std::vector<std::string> a = run;
    a.insert(a.end(), {"--out", out});
    return a;
  };
  auto r = test::run_cli(with_out(dir.path("mine")));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("no runnel run wrote"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_text(dir.path("mine/probes.csv")), "my own gauges\n");

  // Another run's checkpoints, and a folder whose checkpoints/ links to them.
  ASSERT_EQ(test::run_cli({"run", "--generate", "plane", "--steps", "2", "--checkpoint-every", "1",
                           "--quiet", "--out", dir.path("other")})
                .exit_code,
            0);
  std::filesystem::create_directories(dir.path("linked"));
  std::filesystem::create_directory_symlink(dir.path("other/checkpoints"),
                                            dir.path("linked/checkpoints"));
  r = test::run_cli(with_out(dir.path("linked")));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("checkpoints is a link"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("other/checkpoints/step_00000001.h5")));
  EXPECT_TRUE(std::filesystem::exists(dir.path("other/checkpoints/step_00000002.h5")));
}

}  // namespace
}  // namespace runnel
