// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "runnel/core/parameters_toml.hpp"
#include "runnel/models/parameter_table.hpp"

namespace runnel {

// Reads a TOML scenario into validated parameters. Unknown keys, wrong types and out-of-range
// values throw an input error naming the file and the key. A relative terrain.file is resolved
// against the scenario's folder.
Parameters load_scenario(const std::string& path);
// Same, from TOML text (tests; `origin` names the text in errors).
Parameters parse_scenario(const std::string& toml_text, const std::string& origin,
                          const std::string& base_dir = "");

// Every file the parameters name (terrain, graph, masks, uplift, layer thicknesses) as
// (parameter, path): the inputs an output must never replace.
std::vector<std::pair<std::string, std::string>> input_files(const Parameters& params);

}  // namespace runnel
