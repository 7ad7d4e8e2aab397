// SPDX-License-Identifier: MIT
// runnel params: every scenario parameter with its default, unit, range and meaning.
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/models/parameter_table.hpp"

namespace runnel::cli {

void add_params_command(CLI::App& app) {
  auto markdown = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "params", "List every scenario parameter (key, default, unit, range, meaning)");
  cmd->add_flag("--markdown", *markdown, "print docs/parameters.md");
  cmd->callback([markdown] {
    if (*markdown) {
      std::cout << parameters_markdown(parameter_table());
      return;
    }
    auto print = [](const ParamSpec& p, const std::string& key) {
      std::cout << key << " = " << p.default_value << (p.has_unit() ? " [" + p.unit + "]" : "")
                << "\n    " << p.help << "\n";
    };
    for (auto& p : parameter_table()) {
      print(p, p.key);
      if (p.type == ParamType::kEntries)
        for (const ParamSpec& sub : *p.entry_keys) print(sub, p.key + "[]." + sub.key);
    }
  });
}

}  // namespace runnel::cli
