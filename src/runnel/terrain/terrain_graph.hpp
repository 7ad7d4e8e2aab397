// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/heightmap.hpp"

namespace runnel {

class ComputeContext;

// A terrain composed as a graph in TOML (docs/generators.md): nodes are generators, filters and
// input files, edges name inputs, and `output` names the node that is the terrain.
//
//   size = 257          # vertices per side (or [nx, ny])
//   cell = 2.0          # m
//   seed = 1            # the generators' default seed
//   output = "valley"
//   [nodes.base]
//   generator = "varying-hurst"
//   set = { by_height = 1 }
//   [nodes.valley]
//   filter = "power"
//   input = "base"      # or inputs = ["a", "b"]
//   exponent = 2.0
//
// Every key is validated; a cycle is refused naming it ("a → b → a"). Files are relative to the
// graph's folder. `compute` runs the noise generators on the device (same bytes as the host).
Heightmap evaluate_terrain_graph(const std::string& path, ComputeContext* compute = nullptr);
// The same from TOML text; `origin` names it in errors, `base_dir` resolves files.
Heightmap evaluate_terrain_graph_text(const std::string& toml_text, const std::string& origin,
                                      const std::string& base_dir,
                                      ComputeContext* compute = nullptr);

}  // namespace runnel
