// SPDX-License-Identifier: MIT
// runnel info: a summary of a terrain file.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/commands.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/height_steps.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel::cli {
namespace {

// The layer stack of a checkpoint that has one (docs/layers.md), and its loose sediment.
std::optional<std::pair<Strata, std::vector<std::int64_t>>> ground_of(const CheckpointData& d) {
  const StoredField *contacts = nullptr, *sediment = nullptr;
  for (const StoredField& f : d.fields) {
    if (f.name == kGroundContacts) contacts = &f;
    if (f.name == kGroundSediment) sediment = &f;
  }
  if (!contacts || !sediment) return std::nullopt;
  const Parameters params = parse_scenario(d.parameters_toml, "checkpoint parameters");
  return std::make_pair(strata_from_fields(params, d.terrain.nx, d.terrain.ny, contacts->i64,
                                           contacts->components, d.height_quantum),
                        sediment->i64);
}

// The stack as a table: each material's erodibility, rock eroded and exposed share.
void print_ground(const CheckpointData& d, const Strata& s,
                  const std::vector<std::int64_t>& sediment) {
  const MaterialTally t = tally_materials(s, d.height_fixed, sediment);
  const double vq = d.height_quantum * d.terrain.cell * d.terrain.cell;
  std::printf("  layer stack, top first (erodibility, rock eroded, exposed share of the map):\n");
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const double share =
        100.0 * static_cast<double>(t.exposed[m]) / static_cast<double>(s.vertices());
    const bool loose = m >= t.eroded.size();
    const double volume = static_cast<double>(loose ? t.sediment : t.eroded[m]) * vq;
    std::printf("    %-16s x%-6g %12.6g m^3 %s %5.1f %%\n", s.materials[m].name.c_str(),
                s.materials[m].erodibility, volume, loose ? "loose " : "eroded", share);
  }
}

void print_checkpoint_info(const std::string& file, bool json) {
  const CheckpointData d = read_checkpoint(file);
  const auto ground = ground_of(d);
  // Suspended sediment: on the particles (sph), or the grid field (pipe, olsen).
  double suspended = 0;
  for (auto s : d.particles.sediment) suspended += s;
  std::string fields;
  for (const StoredField& f : d.fields) {
    fields += (fields.empty() ? "" : ", ") + f.name;
    if (f.name == "sediment__suspended")
      for (auto s : f.i64) suspended += static_cast<double>(s);
  }
  suspended *= d.height_quantum * d.terrain.cell * d.terrain.cell;
  double eroded = 0, deposited = 0;
  for (std::size_t k = 0; k < d.height_fixed.size(); ++k) {
    const double change = static_cast<double>(d.height_fixed[k] - d.initial_fixed[k]);
    (change < 0 ? eroded : deposited) += std::fabs(change);
  }
  const double q = d.height_quantum * d.terrain.cell * d.terrain.cell;
  // Tectonic uplift (stream-power) is in the change from the initial terrain here; the run's
  // metrics.json measures eroded and deposited from the uplifted surface
  // (Model::erosion_reference), which needs the model's uplift map.
  double uplift = 0;
  for (const auto& [name, value] : d.model_counters)
    if (name == "uplift_quanta") uplift = static_cast<double>(value) * q;
  if (json) {
    std::cout << JsonObject()
                     .add("file", file)
                     .add("schema_version", static_cast<long long>(kCheckpointSchemaVersion))
                     .add("model", d.model)
                     .add("runnel_version", d.runnel_version)
                     .add("source_revision", d.source_revision)
                     .add("nx", d.terrain.nx)
                     .add("ny", d.terrain.ny)
                     .add("cell", d.terrain.cell)
                     .add("origin_x", d.terrain.origin_x)
                     .add("origin_z", d.terrain.origin_z)
                     .add("crs", crs_name(d.terrain.georef.crs_wkt))
                     .add("steps", static_cast<long long>(d.steps))
                     .add("sim_time", d.time)
                     .add("dt", d.dt)
                     .add("particles", static_cast<long long>(d.particles.size()))
                     .add("seed", static_cast<long long>(d.seed))
                     .add("eroded_volume", eroded * q)
                     .add("deposited_volume", deposited * q)
                     .add("suspended_volume", suspended)
                     .add("uplift_volume", uplift)
                     .add("fields", fields)
                     .add("ground",
                          ground ? ground_summary(ground->first, d.height_fixed, ground->second, q)
                                 : JsonObject())
                     .str()
              << "\n";
    return;
  }
  std::printf("%s: runnel checkpoint (schema %lld, %s model, runnel %s, revision %s)\n",
              file.c_str(), static_cast<long long>(kCheckpointSchemaVersion), d.model.c_str(),
              d.runnel_version.c_str(), d.source_revision.c_str());
  std::printf("  terrain %d x %d vertices, cell %g m, heights %.3f .. %.3f m\n", d.terrain.nx,
              d.terrain.ny, d.terrain.cell, d.terrain.min_height(), d.terrain.max_height());
  if (!d.terrain.georef.crs_wkt.empty())
    std::printf("  CRS %s\n", crs_name(d.terrain.georef.crs_wkt).c_str());
  if (d.model == "sph") {
    std::printf("  step %llu, t = %.6g s, dt = %.3g s, %zu particles, seed %lld\n",
                static_cast<unsigned long long>(d.steps), d.time, d.dt, d.particles.size(),
                static_cast<long long>(d.seed));
  } else {
    std::printf("  step %llu, model time %.6g, fields: %s, seed %lld\n",
                static_cast<unsigned long long>(d.steps), d.time,
                fields.empty() ? "none" : fields.c_str(), static_cast<long long>(d.seed));
  }
  std::printf("  eroded %.6g m^3, deposited %.6g m^3, suspended %.6g m^3\n", eroded * q,
              deposited * q, suspended);
  if (uplift > 0)
    std::printf(
        "  uplift %.6g m^3 (eroded and deposited above are changes from the initial terrain, the\n"
        "  uplift included; the run's metrics.json measures them from the uplifted surface)\n",
        uplift);
  if (ground) print_ground(d, ground->first, ground->second);
}

}  // namespace

void add_info_command(CLI::App& app) {
  struct Options {
    std::string file;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("info",
                                 "Summarise a terrain file (.asc, .png, .npy, .tif or another "
                                 "raster GDAL reads) or a checkpoint (.h5)");
  cmd->add_option("file", opt->file, "file to describe")->required();
  cmd->add_flag("--json", opt->json, "print JSON");
  cmd->callback([opt] {
    if (std::filesystem::path(opt->file).extension() == ".h5") {
      print_checkpoint_info(opt->file, opt->json);
      return;
    }
    const Heightmap t = read_terrain(opt->file);
    const HeightSteps steps = height_steps(t);
    if (opt->json) {
      std::cout << JsonObject()
                       .add("file", opt->file)
                       .add("nx", t.nx)
                       .add("ny", t.ny)
                       .add("cell", t.cell)
                       .add("min_height", t.min_height())
                       .add("max_height", t.max_height())
                       .add("volume", t.volume())
                       .add("origin_x", t.origin_x)
                       .add("origin_z", t.origin_z)
                       .add("crs", crs_name(t.georef.crs_wkt))
                       .add("crs_wkt", t.georef.crs_wkt)
                       .merge(steps.json())
                       .str()
                << "\n";
      return;
    }
    std::printf(
        "%s: terrain %d x %d vertices, cell %g m (%g x %g m)\n  heights %.3f .. %.3f m, volume "
        "%.6g m^3\n",
        opt->file.c_str(), t.nx, t.ny, t.cell, (t.nx - 1) * t.cell, (t.ny - 1) * t.cell,
        t.min_height(), t.max_height(), t.volume());
    if (!t.georef.crs_wkt.empty() || t.origin_x != 0 || t.origin_z != 0) {
      std::printf("  lower-left corner (%.10g, %.10g), CRS %s\n", t.origin_x, t.origin_z,
                  crs_name(t.georef.crs_wkt).c_str());
    }
    if (steps.stepped()) std::printf("  stepped: %s\n", steps.caution().c_str());
  });
}

}  // namespace runnel::cli
