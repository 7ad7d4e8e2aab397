// SPDX-License-Identifier: MIT
// compare.png and report.md of runnel compare.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "runnel/compare/compare.hpp"
#include "runnel/ground/geology_picture.hpp"
#include "runnel/io/images.hpp"
#include "runnel/terrain/height_steps.hpp"

namespace runnel::compare {
namespace {

constexpr int kTileVertices = 257;  // larger terrains are subsampled for the figure

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Every `factor`-th vertex of a vertex map, as subsample() takes them from a terrain.
std::vector<int> subsample_map(const std::vector<int>& map, int nx, int ny, int factor) {
  std::vector<int> out;
  for (int j = 0; j < ny; j += factor)
    for (int i = 0; i < nx; i += factor) out.push_back(map[static_cast<std::size_t>(j) * nx + i]);
  return out;
}

// The strata on the subsampled grid (their materials; the contacts are not needed for a picture).
Strata picture_strata(const Strata& s, const Heightmap& grid) {
  Strata p;
  p.nx = grid.nx;
  p.ny = grid.ny;
  p.strata = s.strata;
  p.materials = s.materials;
  return p;
}

double metric(const ModelResult& r, const std::string& name) {
  for (auto& [key, value] : r.terrain_values)
    if (key == name) return value;
  return std::nan("");
}

}  // namespace

void write_compare_png(const std::string& path, const Heightmap& initial,
                       const std::vector<ModelResult>& results) {
  const int factor = std::max(1, (std::max(initial.nx, initial.ny) - 2) / (kTileVertices - 1) + 1);
  const Heightmap before = subsample(initial, factor);
  float lo = before.min_height(), hi = before.max_height();
  std::vector<Heightmap> after;
  for (const ModelResult& r : results) {
    after.push_back(subsample(r.final_terrain, factor));
    lo = std::min(lo, after.back().min_height());
    hi = std::max(hi, after.back().max_height());
  }
  // Each erosion map on its own Δh scale (its 99th percentile of |Δh|, in its title): models that
  // move a hundred times more than others would otherwise leave those blank. The magnitudes are in
  // the table beside the figure.
  std::vector<RgbImage> top, bottom;
  top.push_back(with_title(terrain_picture(before, lo, hi), "initial terrain"));
  for (std::size_t k = 0; k < results.size(); ++k) {
    const std::string name = lower(results[k].model);
    const Heightmap reference = subsample(results[k].erosion_reference, factor);
    const double scale = erosion_scale(reference, after[k]);
    top.push_back(with_title(terrain_picture(after[k], lo, hi), name + ": final"));
    bottom.push_back(with_title(erosion_picture(reference, after[k], scale),
                                name + ": dh +-" + format("%.2g", scale) + " m"));
  }
  // A layered scenario (docs/layers.md): a third row, the geological maps, the initial one first.
  std::vector<RgbImage> geology;
  if (!results.empty() && results.front().strata) {
    const Strata& strata = *results.front().strata;
    const Strata small = picture_strata(strata, before);
    std::vector<int> surface(strata.vertices());
    for (std::size_t k = 0; k < surface.size(); ++k)
      surface[k] = rock_material(strata, k, strata.contact(0, k));
    geology.push_back(with_title(
        geology_picture(small, subsample_map(surface, strata.nx, strata.ny, factor), before),
        "initial geology"));
    for (std::size_t k = 0; k < results.size(); ++k) {
      geology.push_back(with_title(
          geology_picture(small, subsample_map(results[k].exposed, strata.nx, strata.ny, factor),
                          after[k]),
          lower(results[k].model) + ": exposed layer"));
    }
  }
  int tile_w = 0, top_h = 0, bottom_h = 0, geology_h = 0;
  for (auto& t : top) tile_w = std::max(tile_w, t.width), top_h = std::max(top_h, t.height);
  for (auto& b : bottom)
    tile_w = std::max(tile_w, b.width), bottom_h = std::max(bottom_h, b.height);
  for (auto& g : geology)
    tile_w = std::max(tile_w, g.width), geology_h = std::max(geology_h, g.height);
  const int gap = 8, columns = static_cast<int>(top.size());
  RgbImage grid(columns * (tile_w + gap) + gap,
                top_h + bottom_h + 3 * gap + (geology.empty() ? 0 : geology_h + gap));
  for (int c = 0; c < columns; ++c) {
    grid.paste(top[static_cast<std::size_t>(c)], gap + c * (tile_w + gap), gap);
    if (c > 0)
      grid.paste(bottom[static_cast<std::size_t>(c - 1)], gap + c * (tile_w + gap),
                 top_h + 2 * gap);
    if (!geology.empty())
      grid.paste(geology[static_cast<std::size_t>(c)], gap + c * (tile_w + gap),
                 top_h + bottom_h + 3 * gap);
  }
  // Under the initial terrain: what the colours mean.
  const int x = gap + 4, y = top_h + 2 * gap + 8;
  draw_text(grid, x, y, "erosion maps:", 2);
  draw_text(grid, x, y + 24, "each its own scale", 2);
  draw_text(grid, x, y + 48, "red: eroded", 2, 180, 30, 30);
  draw_text(grid, x, y + 72, "blue: deposited", 2, 30, 60, 180);
  draw_text(grid, x, y + 96, "heights " + format("%.4g", lo) + " to", 2);
  draw_text(grid, x, y + 120, format("%.4g", hi) + " m", 2);
  write_png_rgb(path, with_title(grid, "runnel compare: " + std::to_string(results.size()) +
                                           " models, one terrain, one rain budget"));
}

namespace {

// One row a model: its run, its mass balance and the shared metrics.
std::string results_table(const std::vector<ModelResult>& results) {
  std::string md =
      "| model | class | steps | time | rain m³ | eroded m³ | deposited m³ | outflow m³ | balance "
      "(rel) | hypsometric integral | erosion score | mean slope ° | drainage density 1/m | "
      "concavity θ | spectral slope | erosion–flow ρ | stream-power ρ | depressions | short-λ "
      "share | short-λ power after/before |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelResult& r : results) {
    md += "| [" + r.model + "](" + r.folder + "/metrics.json) | " + r.class_name + " | " +
          std::to_string(r.steps) + " | " + format("%.4g", r.time) +
          (r.clock == "s"    ? " s"
           : r.clock == "yr" ? " yr"
                             : "") +
          " | " + format("%.4g", r.rain_volume) + " | " + format("%.4g", r.balance.eroded) + " | " +
          format("%.4g", r.balance.deposited) + " | " + format("%.4g", r.balance.outflow) + " | " +
          format("%.1e", r.balance.relative) + " | " +
          format("%.4f", metric(r, "hypsometric_integral")) + " | " +
          format("%.4f", metric(r, "erosion_score")) + " | " +
          format("%.2f", metric(r, "mean_slope_deg")) + " | " +
          format("%.4g", metric(r, "drainage_density_per_m")) + " | " +
          format("%.3f", metric(r, "concavity_theta")) + " | " +
          format("%.3f", metric(r, "spectral_slope")) + " | " +
          format("%.3f", metric(r, "erosion_flow_correlation")) + " | " +
          format("%.3f", metric(r, "stream_power_correlation")) + " | " +
          format("%.0f", metric(r, "closed_depressions")) + " | " +
          format("%.3f", metric(r, "short_wavelength_dh_share")) + " | " +
          format("%.3f", metric(r, "short_wavelength_power_ratio")) + " |\n";
  }
  return md;
}

// With a layered ground: the rock each model eroded from each material.
std::string layers_table(const std::vector<ModelResult>& results) {
  std::string md;
  if (!results.empty() && results.front().strata) {
    const Strata& strata = *results.front().strata;
    md +=
        "\nThe layered ground (docs/layers.md): the third row of compare.png shows the exposed "
        "layer of each model at the end beside the initial geology. Rock eroded from each "
        "material, m³ (erodibility in brackets):\n\n| model |";
    std::string rule = "|---|";
    for (std::size_t m = 0; m < results.front().eroded_per_material.size(); ++m) {
      md += " " + strata.materials[m].name + " (×" +
            format("%.3g", strata.materials[m].erodibility) + ") |";
      rule += "---|";
    }
    md += "\n" + rule + "\n";
    for (const ModelResult& r : results) {
      md += "| " + r.model + " |";
      for (double v : r.eroded_per_material) md.append(" ").append(format("%.4g", v)).append(" |");
      md += "\n";
    }
  }
  return md;
}

}  // namespace

std::string report_markdown(const std::vector<ModelResult>& results, const RainBudget& budget,
                            const Heightmap& initial, const Options& options) {
  std::string md = "# runnel compare: " + options.scenario_name + "\n\n";
  md += "Terrain " + std::to_string(initial.nx) + " × " + std::to_string(initial.ny) +
        " vertices, cell " + format("%.6g", initial.cell) + " m, heights " +
        format("%.4g", initial.min_height()) + " to " + format("%.4g", initial.max_height()) +
        " m. Rain budget " + format("%.6g", budget.volume) +
        " m³ (the SPH rain: " + format("%.6g", budget.sph_rate) + " particles/s of " +
        format("%.4g", budget.particle_volume) + " m³ for " + format("%.6g", budget.duration) +
        " s); pipe and olsen rain it evenly on every cell, the droplet model as one droplet per "
        "particle volume; thermal has no rain. See docs/models.md.\n\n";
  md +=
      "![initial terrain, then each model's final terrain above its erosion map](compare.png)\n\n";
  md += results_table(results);
  md += layers_table(results);
  // A comparison is only as fair as its least resolved model: say so beside the table.
  std::string cautions;
  const std::string steps = height_steps(initial).caution();
  if (!steps.empty()) cautions += "- terrain: " + steps + "\n";
  for (const ModelResult& r : results)
    if (!r.caution.empty()) cautions += "- " + r.model + ": " + r.caution + "\n";
  if (!cautions.empty()) md += "\nCautions:\n\n" + cautions;
  md += "\nHow each model received the budget (parameters set by runnel compare):\n\n";
  for (const ModelResult& r : results)
    md += "- " + r.model + ": " + (r.setup.empty() ? "the scenario as it is" : r.setup) + "\n";
  md +=
      "\nInitial terrain: hypsometric integral " +
      format("%.4f",
             results.empty() ? std::nan("") : metric(results[0], "hypsometric_integral_initial")) +
      ", erosion score " +
      format("%.4f", results.empty() ? std::nan("") : metric(results[0], "erosion_score_initial")) +
      ", closed depressions " +
      format("%.0f",
             results.empty() ? std::nan("") : metric(results[0], "closed_depressions_initial")) +
      " (docs/metrics.md). Every column for every model is in metrics.csv; each model's folder "
      "holds its pictures, "
      "final terrain (ASC, NPY, HDF5) and metrics.json.\n";
  return md;
}

}  // namespace runnel::compare
