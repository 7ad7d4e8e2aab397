// SPDX-License-Identifier: MIT
// runnel info: a summary of a terrain file.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/io/json.hpp"

namespace runnel::cli {

void add_info_command(CLI::App& app) {
  struct Options {
    std::string file;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("info", "Summarise a terrain file (.asc, .png, .npy)");
  cmd->add_option("file", opt->file, "file to describe")->required();
  cmd->add_flag("--json", opt->json, "print JSON");
  cmd->callback([opt] {
    const Heightmap t = read_terrain(opt->file);
    if (opt->json) {
      std::cout << JsonObject()
                       .add("file", opt->file)
                       .add("nx", t.nx)
                       .add("ny", t.ny)
                       .add("cell", t.cell)
                       .add("min_height", t.min_height())
                       .add("max_height", t.max_height())
                       .add("volume", t.volume())
                       .str()
                << "\n";
      return;
    }
    std::printf(
        "%s: terrain %d x %d vertices, cell %g m (%g x %g m)\n  heights %.3f .. %.3f m, volume "
        "%.6g m^3\n",
        opt->file.c_str(), t.nx, t.ny, t.cell, (t.nx - 1) * t.cell, (t.ny - 1) * t.cell,
        t.min_height(), t.max_height(), t.volume());
  });
}

}  // namespace runnel::cli
