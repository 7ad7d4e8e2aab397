// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runnel/models/grid_model.hpp"
#include "runnel/terrain/thermal.hpp"

namespace runnel {

// The random streams of the pipe's stochastic rounding (rng.hpp: one key per step and stream).
inline constexpr std::uint64_t kPipeErodeStream = 0x70657264ULL;      // "perd"
inline constexpr std::uint64_t kPipeTransportStream = 0x70747273ULL;  // "ptrs"
inline constexpr std::uint64_t kPipeBedloadStream = 0x7062646cULL;    // "pbdl"
// The most quanta of a cell's suspended sediment one transport step shares among its pipes
// (pipe.cl's pipe_send computes in 32 bits); a cell holding more keeps the rest for later steps.
inline constexpr long long kPipeSendable = 1LL << 30;
// The water leaving over the edges is counted in whole counts of this depth over a cell (m): exact
// integer totals, the same on every device, good for 9·10⁹ cells' worth of water a face.
inline constexpr double kPipeWaterCountDepth = 1e-9;

struct PipeSettings {
  // The pipe.* parameters (defaults, units, meaning: the table in pipe_model.cpp).
  double rain;         // m/s of water on every cell
  double area;         // A, pipe cross-section, m²
  double gravity;      // m/s²
  double capacity;     // K_c, s (capacity = K_c · sin α · |v|, in m of height)
  double dissolve;     // K_s, 1/s
  double deposit;      // K_d, 1/s
  double evaporation;  // K_e, 1/s
  double manning_n;    // s/m^(1/3); 0: no bed friction (Mei 2007)
  double min_tilt;     // smallest sin α in the capacity
  double cfl;
  double cfl_depth;       // m: thinner water does not limit the step
  double dt_min;          // s: a shorter step stops the run
  double dt_max;          // s
  std::string transport;  // "upwind" or "semi-lagrangian"
  std::string edges;      // "outflow" or "closed"
  std::string law;        // "capacity" (Mei's suspended load) or "bedload" (Wong & Parker)
  std::string flux;       // "pipes" (Mei), "local-inertial" (Bates et al. 2010) or "godunov" (HLL)
  bool inertial() const { return flux == "local-inertial"; }
  bool godunov() const { return flux == "godunov"; }
  bool bedload() const { return law == "bedload"; }
  bool closed() const { return edges == "closed"; }
  // Mei's advection (not conserving; the loss is reported)
  bool semi_lagrangian() const { return transport == "semi-lagrangian"; }
  static PipeSettings from(const Parameters& params);
  std::string build_options() const;
};

// Erosion_Mei2007: virtual-pipe shallow water with erosion (Mei, Decaudin & Hu 2007), host side of
// cl/models/pipe.cl. Each step is adaptive, Δt = min(dt_max, CFL · l / (sqrt(g · d_max) +
// |v|_max)); terrain + suspended sediment + outflow are conserved exactly (integer quanta,
// mass-conserving upwind transport).
class PipeModel final : public GridModel {
 public:
  static const ModelInfo& model_info();
  PipeModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  const ModelInfo& info() const override { return model_info(); }

  double dt() const { return dt_; }
  void limit_next_step(double most) override {
    if (most > 0) dt_ = std::min(dt_, most);
  }
  std::vector<float> depth() { return state_.download_float(kSurfaceWaterDepth); }
  long long outflow_quanta() override;
  long long lost_quanta() override;
  std::array<double, 4> edge_water_outflow() override;
  // Bed quanta the bed load has moved out of cells so far (0 under the capacity law).
  long long bed_moved_quanta();
  double rain_volume() override;
  double scenario_rain_rate() const override { return settings_.rain; }
  JsonObject diagnostics() override;
  std::string caution() override;
  std::vector<std::pair<std::string, double>> summary_values() override;
  // The flow's Froude number (the water's inside the map, weighted by its discharge; pipe_stats),
  // its largest so far.
  double flow_froude_max() const { return static_cast<double>(flow_froude_max_micro_) * 1e-6; }

 protected:
  double take_step() override;
  std::vector<std::pair<std::string, std::int64_t>> counters() override;
  void restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) override;
  double next_dt() const override { return dt_; }
  void restore_next_dt(double dt) override { dt_ = dt; }
  double scratch_bytes() const override;

 private:
  void choose_next_dt();
  void count_edge_water(cl::Buffer& flux, float dt);
  double water_count_volume() const;
  std::array<long long, 4> edge_water_counts();
  PipeSettings settings_;
  double dt_ = 0;
  // In millionths, an integer so that a checkpoint carries it exactly.
  std::int64_t flow_froude_max_micro_ = 0;
  int depth_, flux_, velocity_, sediment_;  // GridState handles
  void transport(cl::Buffer& sediment, cl::Buffer& flux, cl::Buffer& velocity, float dt);
  // pipe.law = "bedload": the grains the flow rolls along the bed, moved between the cells'
  // heights.
  void start_bed_load(ComputeContext& compute, cl::Program& program, const Parameters& params);
  void move_bed_load(cl::Buffer& depth, cl::Buffer& flux, float dt);
  void relax_talus(double dt);
  cl::Buffer bed_sent_, height_next_, bed_moved_;  // bed load only
  cl::Buffer old_flux_;                            // local-inertial only: the step's copy
  cl::Buffer face_flux_;    // godunov only: each cell's right and lower faces' HLL fluxes
  cl::Buffer slopes_;       // godunov only: each cell's limited bed and depth slopes along x and z
  cl::Buffer edge_before_;  // godunov only: the first column's left and first row's upper faces
  Kernel edges_kernel_;     // godunov only: the faces on the map's edges
  Kernel bedload_kernel_;
  std::unique_ptr<ThermalRelaxation>
      talus_;  // bed load only: slopes above the angle of repose slide
  double talus_interval_ = 0;
  cl::Buffer previous_depth_, capacity_, cfl_speed2_, sediment_next_, sent_, stats_, outflow_,
      lost_;
  cl::Buffer edge_water_;  // counts of water out through each edge face (pipe_edge_water)
  Kernel edge_water_kernel_;
  Kernel slopes_kernel_;  // godunov only
  cl::Buffer sendable_;   // pipe_erode's 32-bit copy of the sediment for pipe_send (pipe.cl)
  Kernel flux_kernel_, water_kernel_, erode_kernel_, send_kernel_, receive_kernel_,
      edge_outflow_kernel_, advect_kernel_, stats_kernel_;
};

}  // namespace runnel
