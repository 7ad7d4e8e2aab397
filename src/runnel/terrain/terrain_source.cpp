// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_source.hpp"

#include "runnel/terrain/terrain_graph.hpp"

#include "runnel/core/error.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

Heightmap load_terrain(const Parameters& params) {
  const std::string& file = params.text("terrain.file");
  if (!file.empty()) {
    ReadOptions options;
    options.nodata =
        params.text("terrain.nodata") == "refuse" ? NodataPolicy::kRefuse : NodataPolicy::kFill;
    // terrain.cell is the cell of a file that carries none of its own, or of every file when
    // terrain.cell_from_file is false.
    if (params.boolean("terrain.cell_from_file"))
      options.cell_if_none = params.real("terrain.cell");
    else
      options.cell = params.real("terrain.cell");
    Heightmap terrain = read_terrain(file, options);
    return terrain;
  }
  const std::string& graph = params.text("terrain.graph");
  if (!graph.empty()) return evaluate_terrain_graph(graph);
  const int size = static_cast<int>(params.integer("terrain.size"));
  try {
    return generate_terrain(
        params.text("terrain.generator"), size, size, params.real("terrain.cell"),
        static_cast<std::uint64_t>(params.integer("terrain.seed")), params.generator_values());
  } catch (const Error& e) {
    // Name the scenario key rather than the CLI flag the generator speaks of.
    std::string msg = e.what();
    if (msg.rfind("--set ", 0) == 0) msg = "terrain.set." + msg.substr(6);
    throw Error(e.code(), msg);
  }
}

}  // namespace runnel
