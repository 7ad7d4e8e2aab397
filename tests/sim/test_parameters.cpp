// SPDX-License-Identifier: MIT
// Scenario files and --set: every key validated, errors name the key; docs agree with the table.
#include <gtest/gtest.h>

#include <set>

#include "runnel/core/error.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/terrain/terrain_source.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    return e.what();
  }
  return "no error";
}

TEST(Parameters, DefaultsComeFromTheTable) {
  const Parameters p = default_parameters();
  EXPECT_EQ(p.integer("terrain.size"), 257);
  EXPECT_DOUBLE_EQ(p.real("terrain.cell"), 1.0);
  EXPECT_EQ(p.text("terrain.generator"), "fbm");
  EXPECT_TRUE(p.boolean("terrain.cell_from_file"));
}

TEST(Parameters, ScenarioValuesAndOverridesApply) {
  Parameters p = parse_scenario(
      "[terrain]\nsize = 65\ncell = 2\ngenerator = \"cone\"\n[terrain.set]\nradius = 0.3\n",
      "s.toml");
  EXPECT_EQ(p.integer("terrain.size"), 65);
  EXPECT_DOUBLE_EQ(p.real("terrain.cell"), 2.0);  // an integer is a valid real
  EXPECT_DOUBLE_EQ(p.generator_values().at("radius"), 0.3);
  apply_overrides(p, {"terrain.size=33", "terrain.set.radius=0.2"});
  EXPECT_EQ(p.integer("terrain.size"), 33);
  EXPECT_EQ(load_terrain(p).nx, 33);
  EXPECT_DOUBLE_EQ(p.generator_values().at("radius"), 0.2);
}

TEST(Parameters, BadScenariosNameTheKey) {
  EXPECT_NE(
      error_of([] { parse_scenario("[terrain]\nsizee = 3\n", "s.toml"); }).find("terrain.sizee"),
      std::string::npos);
  EXPECT_NE(error_of([] { parse_scenario("[bogus]\nx = 3\n", "s.toml"); }).find("[bogus]"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_scenario("[terrain]\nsize = \"big\"\n", "s.toml");
            }).find("terrain.size"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_scenario("[terrain]\ncell = 0\n", "s.toml");
            }).find("outside the valid range"),
            std::string::npos);
  EXPECT_NE(
      error_of([] { parse_scenario("[terrain]\ncell = -1.0\n", "s.toml"); }).find("terrain.cell"),
      std::string::npos);
  // The range carries the unit, and a dimensionless one ("1") reads as no unit at all.
  EXPECT_NE(error_of([] { parse_scenario("[terrain]\ncell = 0\n", "s.toml"); }).find("] m"),
            std::string::npos);
  const std::string cfl = error_of([] { parse_scenario("[sph]\ncfl = 0\n", "s.toml"); });
  EXPECT_EQ(cfl.substr(cfl.size() - 1), "]") << cfl;
  EXPECT_NE(error_of([] {
              parse_scenario("[terrain]\ngenerator = \"volcano\"\n", "s.toml");
            }).find("volcano"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_scenario("[terrain\nsize = 3\n", "s.toml"); }).find("s.toml:1"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_scenario("[terrain.set]\nbogus = 1\n", "s.toml");
              load_terrain(parse_scenario("[terrain.set]\nbogus = 1\n", "s.toml"));
            }).find("terrain.set.bogus"),
            std::string::npos);
  Parameters p = default_parameters();
  EXPECT_NE(error_of([&] { apply_overrides(p, {"run.sed=3"}); }).find("run.sed"),
            std::string::npos);
  EXPECT_NE(error_of([&] { apply_overrides(p, {"terrain.size"}); }).find("key=value"),
            std::string::npos);
  EXPECT_NE(error_of([&] { apply_overrides(p, {"terrain.size=1.5"}); }).find("integer"),
            std::string::npos);
}

// A scenario's terrain.cell is the cell of a file that carries none (NPY, a foreign PNG); an ASC's
// own cell wins unless terrain.cell_from_file is false. (An NPY terrain used to come in at 1 m
// whatever the scenario said.)
TEST(Parameters, TerrainCellAppliesToFilesThatCarryNone) {
  test::ScratchDir dir;
  const Heightmap hills = generate_terrain("fbm", 17, 17, 83.0, 3, {});
  write_terrain(dir.path("t.npy"), hills);
  write_terrain(dir.path("t.asc"), hills);
  for (const char* file : {"t.npy", "t.asc"}) {
    for (const bool from_file : {true, false}) {
      Parameters p = default_parameters();
      p.set("terrain.file", dir.path(file));
      p.set("terrain.cell", 2.5);
      p.set("terrain.cell_from_file", from_file);
      const bool carries_cell = std::string(file) == "t.asc";
      EXPECT_EQ(load_terrain(p).cell, carries_cell && from_file ? 83.0 : 2.5)
          << file << ", cell_from_file " << from_file;
    }
  }
}

TEST(Parameters, EveryKeyIsDeclaredOnce) {
  std::set<std::string> keys;
  for (auto& spec : parameter_table())
    EXPECT_TRUE(keys.insert(spec.key).second) << spec.key << " declared twice";
}

TEST(Parameters, DefaultScenarioLoads) {
  const Parameters p = load_scenario(test::source_dir() + "/data/scenarios/default.toml");
  const Heightmap t = load_terrain(p);
  EXPECT_EQ(t.nx, 129);
  EXPECT_EQ(t.ny, 129);
  EXPECT_EQ(t.cell, 2.0);
}

TEST(Parameters, DocsAreGeneratedFromTheTable) {
  const std::string docs = test::read_text(test::source_dir() + "/docs/parameters.md");
  EXPECT_EQ(docs, parameters_markdown(parameter_table()))
      << "regenerate with: build/runnel params --markdown > docs/parameters.md";
}

}  // namespace
}  // namespace runnel
