// SPDX-License-Identifier: MIT
// The parameter table: every scenario key of runnel, with its default, unit, range and meaning.
#include "runnel/sim/parameters.hpp"

namespace runnel {

const std::vector<ParamSpec>& parameter_table() {
  using T = ParamType;
  static const std::vector<ParamSpec> table = {
      // terrain: where the heightmap comes from
      {"terrain.file",
       T::kString,
       "\"\"",
       "",
       0,
       0,
       {},
       "terrain file (.asc, .png, .npy), relative to the scenario file; empty: use "
       "terrain.generator"},
      {"terrain.generator",
       T::kString,
       "\"fbm\"",
       "",
       0,
       0,
       {"diamond-square", "fault", "fbm", "ridged", "crooked", "pyramid", "hemisphere", "plane",
        "cone", "v-valley"},
       "generator used when terrain.file is empty; its own parameters go in [terrain.set]"},
      {"terrain.size",
       T::kInteger,
       "257",
       "vertices",
       2,
       32768,
       {},
       "generated terrain: vertices per side"},
      {"terrain.cell",
       T::kReal,
       "1.0",
       "m",
       1e-6,
       1e6,
       {},
       "cell size (vertex spacing); for files, overrides the file's own when "
       "terrain.cell_from_file is false"},
      {"terrain.cell_from_file",
       T::kBool,
       "true",
       "",
       0,
       0,
       {},
       "take the cell size from the terrain file when it has one (ASC, runnel PNG)"},
      {"terrain.seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "generator seed"},
      {"terrain.nodata",
       T::kString,
       "\"fill\"",
       "",
       0,
       0,
       {"fill", "refuse"},
       "NODATA cells in an ASCII grid: fill from neighbours, or refuse the file"},
      // run: the simulation as a whole
      {"run.seed",
       T::kInteger,
       "1",
       "1",
       0,
       9.2e18,
       {},
       "seed of the simulation's random numbers (rain)"},
  };
  return table;
}

}  // namespace runnel
