// SPDX-License-Identifier: MIT
// Terrain graphs (docs/generators.md): the shipped examples, each filter against its definition
// computed here, file inputs, scenarios that start from a graph, and every malformed graph refused
// with a message naming the node (a cycle by its members).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runnel/core/error.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/filters.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_graph.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/terrain/terrain_source.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

const char* kHeader = "size = 33\ncell = 2.0\nseed = 4\n";

Heightmap graph(const std::string& body, const std::string& base_dir = "") {
  return evaluate_terrain_graph_text(std::string(kHeader) + body, "g.toml", base_dir);
}

std::string error_of(const std::string& body) {
  try {
    graph(body);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    return e.what();
  }
  return "no error";
}

TEST(TerrainGraph, TheShippedExamplesEvaluate) {
  for (const char* name : {"jourdan_valley", "jourdan_mountains_plain"}) {
    const Heightmap t =
        evaluate_terrain_graph(test::source_dir() + "/data/graphs/" + name + ".toml");
    EXPECT_EQ(t.nx, 257) << name;
    EXPECT_GT(t.max_height(), t.min_height()) << name;
    for (float h : t.h) ASSERT_TRUE(std::isfinite(h)) << name;
  }
}

TEST(TerrainGraph, FiltersDoWhatTheySay) {
  const Heightmap a = generate_terrain("fbm", 33, 33, 2.0, 4);
  const Heightmap b = generate_terrain("spectral", 33, 33, 2.0, 4);
  const Heightmap c = generate_terrain("circles", 33, 33, 2.0, 4);
  const std::string nodes =
      "[nodes.a]\ngenerator = \"fbm\"\n[nodes.b]\ngenerator = \"spectral\"\n"
      "[nodes.c]\ngenerator = \"circles\"\n";
  const Heightmap max =
      graph("output = \"m\"\n" + nodes + "[nodes.m]\nfilter = \"max\"\ninputs = [\"a\", \"b\"]\n");
  const Heightmap median =
      graph("output = \"m\"\n" + nodes +
            "[nodes.m]\nfilter = \"median\"\ninputs = [\"a\", \"b\", \"c\"]\n");
  const Heightmap power = graph("output = \"p\"\n" + nodes +
                                "[nodes.p]\nfilter = \"power\"\ninput = \"a\"\nexponent = 3\n");
  const Heightmap terrace =
      graph("output = \"t\"\n" + nodes +
            "[nodes.t]\nfilter = \"terrace\"\ninput = \"a\"\nsteps = 4\nsharpness = 0.99\n");
  const Heightmap blend = graph("output = \"x\"\n" + nodes +
                                "[nodes.x]\nfilter = \"blend\"\ninputs = [\"a\", \"b\", \"c\"]\n");
  const double lo = a.min_height(), range = a.max_height() - lo;
  const double clo = c.min_height(), crange = c.max_height() - clo;
  std::vector<float> treads;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(max.h[k], std::max(a.h[k], b.h[k]));
    float v[3] = {a.h[k], b.h[k], c.h[k]};
    std::sort(v, v + 3);
    EXPECT_EQ(median.h[k], v[1]);
    EXPECT_NEAR(power.h[k], lo + range * std::pow((a.h[k] - lo) / range, 3.0), 1e-3 * range);
    const double w = (c.h[k] - clo) / crange;
    EXPECT_NEAR(blend.h[k], a.h[k] * (1 - w) + b.h[k] * w, 1e-4 * range);
    treads.push_back(terrace.h[k]);
  }
  // Terraces: nearly every vertex sits on a tread, lo + range·k/4 (the rises are 1 % of each step).
  std::size_t on_treads = 0;
  for (float h : treads) {
    const double k = (h - lo) / range * 4;
    on_treads += std::fabs(k - std::round(k)) < 1e-3;
  }
  EXPECT_GE(on_treads, treads.size() * 95 / 100);
}

TEST(TerrainGraph, FileInputsAreResampledAndScenariosStartFromAGraph) {
  test::ScratchDir dir;
  write_terrain(dir.path("dem.npy"), generate_terrain("cone", 17, 17, 1.0, 1));
  test::write_text(dir.path("g.toml"),
                   std::string(kHeader) +
                       "output = \"o\"\n[nodes.dem]\nfile = \"dem.npy\"\n"
                       "[nodes.o]\nfilter = \"scale\"\ninput = \"dem\"\nfactor = 2\n");
  testing::internal::CaptureStderr();
  const Heightmap t = evaluate_terrain_graph(dir.path("g.toml"));
  EXPECT_NE(testing::internal::GetCapturedStderr().find("resampled"), std::string::npos);
  EXPECT_EQ(t.nx, 33);
  EXPECT_NEAR(t.at(16, 16), 2 * generate_terrain("cone", 17, 17, 1.0, 1).at(8, 8), 1e-3);
  test::write_text(dir.path("s.toml"), "[terrain]\ngraph = \"g.toml\"\n");
  const Heightmap from_scenario = load_terrain(load_scenario(dir.path("s.toml")));
  EXPECT_EQ(from_scenario.h, t.h);
}

TEST(TerrainGraph, MalformedGraphsAreRefusedNamingTheNode) {
  EXPECT_NE(
      error_of("output = \"a\"\n[nodes.a]\nfilter = \"max\"\ninputs = [\"b\", \"c\"]\n"
               "[nodes.b]\nfilter = \"smooth\"\ninput = \"a\"\n[nodes.c]\ngenerator = \"fbm\"\n")
          .find("cycle: a → b → a"),
      std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\nfilter = \"smooth\"\ninput = \"a\"\n")
                .find("cycle: a → a"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\nfilter = \"blur\"\ninput = "
                     "\"b\"\n[nodes.b]\ngenerator = \"fbm\"\n")
                .find("nodes.a.filter: unknown filter 'blur'"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\ngenerator = \"fbm\"\ncolour = 1\n")
                .find("nodes.a.colour"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\ngenerator = \"fbm\"\nset = { hurst = 9 }\n")
                .find("nodes.a.set.hurst"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\nfilter = \"max\"\ninput = "
                     "\"b\"\n[nodes.b]\ngenerator = \"fbm\"\n")
                .find("takes 2 or more inputs, got 1"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"z\"\n[nodes.a]\ngenerator = \"fbm\"\n").find("no node named 'z'"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\nfilter = \"smooth\"\ninput = \"q\"\n")
                .find("input 'q' is not a node"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\ngenerator = \"fbm\"\nfilter = \"smooth\"\n")
                .find("exactly one"),
            std::string::npos);
  EXPECT_NE(error_of("output = \"a\"\n[nodes.a]\nfilter = \"power\"\ninput = \"b\"\nexponent = "
                     "-1\n[nodes.b]\ngenerator = \"fbm\"\n")
                .find("nodes.a.exponent"),
            std::string::npos);
}

TEST(TerrainGraph, DocsDescribeEveryGeneratorAndFilter) {
  const std::string docs = test::read_text(test::source_dir() + "/docs/generators.md");
  for (const GeneratorSpec& g : generators())
    EXPECT_NE(docs.find("| `" + g.name + "` |"), std::string::npos) << g.name;
  for (const FilterSpec& f : filters())
    EXPECT_NE(docs.find("`" + f.name + "`"), std::string::npos) << f.name;
}

TEST(TerrainGraph, TheCommandLineComposesAGraphAndRefusesACycle) {
  test::ScratchDir dir;
  const auto ok =
      test::run_cli({"generate", "--graph", test::source_dir() + "/data/graphs/jourdan_valley.toml",
                     "-o", dir.path("v.npy"), "--picture", dir.path("v.png")});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(read_terrain(dir.path("v.npy")).nx, 257);
  test::write_text(dir.path("cycle.toml"),
                   std::string(kHeader) +
                       "output = \"a\"\n[nodes.a]\nfilter = \"smooth\"\ninput = \"b\"\n"
                       "[nodes.b]\nfilter = \"smooth\"\ninput = \"a\"\n");
  const auto bad =
      test::run_cli({"generate", "--graph", dir.path("cycle.toml"), "-o", dir.path("c.npy")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("cycle: a → b → a"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  const auto bench = test::run_cli({"bench", "generate", "--size", "64", "--steps", "1"});
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("\"generator\": \"value-noise\""), std::string::npos);
  EXPECT_GT(test::json_number(bench.out, "vertices_per_second"), 0.0);
}

}  // namespace
}  // namespace runnel
