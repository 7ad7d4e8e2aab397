// SPDX-License-Identifier: MIT
// Built from src/runnel/core/ alone (tests/CMakeLists.txt), without the models, the simulation or
// the drivers: if a core file called into a layer above it, this program would not link. It also
// shows that the parameter machinery serves any table, not only runnel's.
#include <gtest/gtest.h>

#include <utility>

#include "runnel/core/error.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/core/parameters_toml.hpp"

namespace runnel {
namespace {

const ParameterTable& pond_table() {
  using T = ParamType;
  static const ParameterTable table = {
      {"pond.depth", T::kReal, "1.5", "m", 0, 10, {}, "water depth"},
      {"pond.fish", T::kInteger, "3", "1", 0, 100, {}, "fish"},
      {"pond.name", T::kString, "\"mill\"", "", 0, 0, {"mill", "duck"}, "which pond"},
  };
  return table;
}

TEST(CoreAlone, ParametersServeAForeignTable) {
  Parameters p(pond_table());
  EXPECT_DOUBLE_EQ(p.real("pond.depth"), 1.5);
  EXPECT_EQ(p.integer("pond.fish"), 3);
  EXPECT_EQ(p.text("pond.name"), "mill");
  EXPECT_FALSE(p.was_set("pond.depth"));
  p.set_text("pond.depth", "2.25");
  EXPECT_DOUBLE_EQ(p.real("pond.depth"), 2.25);
  EXPECT_TRUE(p.was_set("pond.depth"));
  for (const auto& [key, text] :
       {std::pair{"pond.depth", "11"},         // out of range
        std::pair{"pond.name", "\"lake\""},    // not a choice
        std::pair{"run.model", "\"sph\""}}) {  // runnel's key, not this table's
    try {
      p.set_text(key, text);
      ADD_FAILURE() << key << " = " << text << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(find_param(pond_table(), "pond.fish"), &pond_table()[1]);
  EXPECT_EQ(find_param(pond_table(), "terrain.cell"), nullptr);
}

TEST(CoreAlone, TomlTextReadsBackToTheSameValues) {
  Parameters p(pond_table());
  read_parameters_toml(p, "[pond]\ndepth = 0.125\nname = \"duck\"\n", "pond.toml");
  EXPECT_DOUBLE_EQ(p.real("pond.depth"), 0.125);
  EXPECT_EQ(p.text("pond.name"), "duck");
  Parameters again(pond_table());
  read_parameters_toml(again, parameters_toml(p), "written");
  EXPECT_EQ(again.values(), p.values());
  try {
    read_parameters_toml(again, "[lake]\ndepth = 1\n", "lake.toml");
    ADD_FAILURE() << "a table this program does not have was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("[lake]"), std::string::npos) << e.what();
  }
}

TEST(CoreAlone, HeightmapBuildsWithoutTheLayersAbove) {
  Heightmap h(3, 2, 0.5f);
  h.at(2, 1) = 4.0f;
  EXPECT_EQ(h.at(2, 1), 4.0f);
  EXPECT_EQ(h.at(0, 0), 0.0f);
}

}  // namespace
}  // namespace runnel
