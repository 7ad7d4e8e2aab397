// SPDX-License-Identifier: MIT
// runnel devices: the OpenCL platforms and devices, and which one runnel picks by default.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"

namespace runnel::cli {

void add_devices_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("devices",
                                 "List OpenCL platforms and devices (select one with --device or "
                                 "$RUNNEL_DEVICE: an index, P:D, gpu, cpu or part of the name)");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "print JSON instead of a table");
  cmd->callback([json] {
    const auto devices = list_devices();
    const DeviceInfo chosen = select_device("");
    if (*json) {
      std::vector<JsonObject> list;
      for (const auto& d : devices) {
        list.push_back(JsonObject()
                           .add("index", d.index)
                           .add("platform", d.platform)
                           .add("name", d.name)
                           .add("type", d.type)
                           .add("version", d.version)
                           .add("compute_units", d.compute_units)
                           .add("global_memory_bytes", d.global_memory)
                           .add("lanes", device_lanes(d))
                           .add("default", d.index == chosen.index));
      }
      std::cout << JsonObject().add("devices", list).str() << "\n";
      return;
    }
    for (const auto& d : devices) {
      std::printf(
          "%s [%d] platform %d device %d: %s (%s)\n      %s; %s; %u compute units, %.1f GiB global "
          "memory, "
          "%.0f KiB local memory, %u lanes\n",
          d.index == chosen.index ? "*" : " ", d.index, d.platform_index, d.device_index,
          d.name.c_str(), d.type.c_str(), d.platform.c_str(), d.version.c_str(), d.compute_units,
          d.global_memory / 1073741824.0, d.local_memory / 1024.0, device_lanes(d));
    }
    std::printf("* = the default device\n");
  });
}

}  // namespace runnel::cli
