// SPDX-License-Identifier: MIT
// A terrain with NODATA holes refused on request: the message names the scenario key and the flag
// that fill them, and following it works.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace runnel {
namespace {

TEST(CliNodata, TheRefusalNamesTheKeyThatFillsTheHolesAndTheKeyWorks) {
  test::ScratchDir dir;
  std::string asc =
      "ncols 20\nnrows 20\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
  for (int j = 0; j < 20; ++j) {
    for (int i = 0; i < 20; ++i) asc += (i == 7 && j == 9) ? "-9999 " : std::to_string(i + j) + " ";
    asc += "\n";
  }
  test::write_text(dir.path("holes.asc"), asc);
  const std::vector<std::string> run = {"run",     "--terrain", dir.path("holes.asc"), "--model",
                                        "thermal", "--set",     "run.iterations=1",    "--quiet"};
  auto refuse = run;
  refuse.insert(refuse.end(), {"--set", "terrain.nodata=\"refuse\"", "--out", dir.path("a")});
  const auto r = test::run_cli(refuse);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("1 NODATA cells"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("terrain.nodata = \"fill\""), std::string::npos) << r.err;
  auto fill = run;
  fill.insert(fill.end(), {"--set", "terrain.nodata=\"fill\"", "--out", dir.path("b")});
  const auto f = test::run_cli(fill);
  EXPECT_EQ(f.exit_code, 0) << f.err;
  // runnel convert names its own flag, which exists.
  const auto c =
      test::run_cli({"convert", dir.path("holes.asc"), dir.path("c.npy"), "--nodata", "refuse"});
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("--nodata fill"), std::string::npos) << c.err;
  EXPECT_EQ(test::run_cli({"convert", dir.path("holes.asc"), dir.path("d.npy"), "--nodata", "fill"})
                .exit_code,
            0);
}

}  // namespace
}  // namespace runnel
