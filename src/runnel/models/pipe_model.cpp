// SPDX-License-Identifier: MIT
#include "runnel/models/pipe_model.hpp"
#include "runnel/core/text.hpp"

#include "runnel/ground/bedload.hpp"
#include "runnel/ground/ground_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/rng.hpp"
#include "runnel/core/settings_table.hpp"

namespace runnel {
namespace {
constexpr int kStatBlocks = 1024;
}

namespace {

// clang-format off
const SettingsTable<PipeSettings> kPipeTable = {
      // pipe: virtual-pipe shallow water with erosion (Mei, Decaudin, Hu 2007)
      {"pipe.rain", "0.01", "m/s", 0, 1e3, {}, "rain on every cell", &PipeSettings::rain, "PIPE_RAIN"},
      {"pipe.area", "1", "m^2", 1e-6, 1e6, {}, "A, cross-section of the virtual pipes", &PipeSettings::area, "PIPE_AREA"},
      {"pipe.gravity", "9.81", "m/s^2", 0, 100, {}, "gravity", &PipeSettings::gravity, "PIPE_GRAVITY"},
      {"pipe.capacity", "0.05", "s", 0, 1e6, {}, "K_c: capacity = K_c · max(sin α, min_tilt) · |v| (m of height)", &PipeSettings::capacity, "PIPE_CAPACITY"},
      {"pipe.dissolve", "100", "1/s", 0, 1e6, {}, "K_s, rate at which the free capacity is dissolved: (1 − exp(−K_s·Δt))(C − s) per step", &PipeSettings::dissolve, "PIPE_DISSOLVE"},
      {"pipe.deposit", "100", "1/s", 0, 1e6, {}, "K_d, rate at which the excess load is deposited: (1 − exp(−K_d·Δt))(s − C) per step", &PipeSettings::deposit, "PIPE_DEPOSIT"},
      {"pipe.evaporation", "0.05", "1/s", 0, 1e3, {}, "K_e, evaporation rate", &PipeSettings::evaporation, "PIPE_EVAPORATION"},
      {"pipe.manning_n", "0.03", "s/m^(1/3)", 0, 1, {}, "Manning's n of the bed friction on the pipe flow (the SPH model's law; not in Mei 2007): without it thin films run as fast as the flux limiter lets them, whatever the time step; 0: Mei's frictionless pipes", &PipeSettings::manning_n},
      {"pipe.min_tilt", "0.05", "1", 0, 1, {}, "smallest sin α in the capacity", &PipeSettings::min_tilt, "PIPE_MIN_TILT"},
      {"pipe.cfl", "0.25", "1", 0.01, 1, {}, "Δt ≤ cfl · l / (sqrt(g d_max) + |v|_max)", &PipeSettings::cfl},
      {"pipe.cfl_depth", "0.01", "m", 0, 1e3, {}, "water thinner than this does not count in the CFL limit (a thin film's flux over its depth is not a wave speed; the flux limit keeps it non-negative)", &PipeSettings::cfl_depth, "PIPE_CFL_DEPTH"},
      {"pipe.dt_min", "1e-6", "s", 0, 100, {}, "smallest time step: a step the CFL limit would make shorter stops the run with an error (a collapsing step means the flow has blown up)", &PipeSettings::dt_min},
      {"pipe.dt_max", "0.05", "s", 1e-9, 100, {}, "largest time step", &PipeSettings::dt_max},
      {"pipe.transport", "\"upwind\"", "", 0, 0, {"upwind", "semi-lagrangian"}, "sediment transport: upwind (mass-conserving, sediment leaves with the water) or semi-lagrangian (Mei 2007's advection; not conserving, the loss is reported as lost_volume)", &PipeSettings::transport},
      {"pipe.edges", "\"outflow\"", "", 0, 0, {"outflow", "closed"}, "outflow (outside cells have b = d = 0) or closed", &PipeSettings::edges},
      {"pipe.flux", "\"godunov\"", "", 0, 0, {"pipes", "local-inertial", "godunov"}, "the water's flux between cells: pipes (Mei 2007: two one-way pipes a face of cross-section pipe.area, whose waves travel at about sqrt(g A / l)), local-inertial (Bates, Horritt & Fewtrell 2010: one signed flux a face over the water's own depth, waves at sqrt(g d), no advection) or godunov (the shallow-water equations in finite volumes: HLL fluxes on Audusse's hydrostatic reconstruction, with advection, so supercritical flow runs as it does; docs/models.md, \"pipe\")", &PipeSettings::flux},
      {"pipe.law", "\"capacity\"", "", 0, 0, {"capacity", "bedload"}, "erosion law: capacity (Mei 2007: the water dissolves the bed up to a transport capacity and carries it in suspension) or bedload (Wong & Parker's Meyer-Peter & Müller from the Shields stress of the Manning bed shear, the bed by Exner with porosity, talus sliding at thermal.talus_angle every thermal.interval; sediment.* gives the grains)", &PipeSettings::law},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> pipe_parameters() {
  return settings_specs(kPipeTable);
}

PipeSettings PipeSettings::from(const Parameters& p) {
  return read_settings(p, kPipeTable);
}

std::string PipeSettings::build_options() const {
  return settings_defines(*this, kPipeTable) + " -DPIPE_CLOSED=" + (closed() ? "1" : "0") +
         float_define("PIPE_GRAVITY_N2", gravity * manning_n * manning_n) +
         " -DPIPE_FRICTION_ON=" + (manning_n > 0 ? "1" : "0") +
         " -DPIPE_SENDABLE=" + std::to_string(kPipeSendable) + "L";
}

const ModelInfo& PipeModel::model_info() {
  static const ModelInfo info{
      "pipe",
      "Erosion_Mei2007",
      "X. Mei, P. Decaudin, B.-G. Hu: Fast hydraulic erosion simulation and visualization on GPU, "
      "Pacific Graphics 2007",
      "pipe",
      ModelClock::kSeconds,
      true,
      {{kTopographicElevation, FieldIntent::kInOut},
       {kSurfaceWaterDepth, FieldIntent::kOut},
       {kSurfaceWaterOutflux, FieldIntent::kOut},
       {kSurfaceWaterVelocity, FieldIntent::kOut},
       {kSedimentSuspended, FieldIntent::kOut}},
      {"flow_froude_max"},
      224};  // 120 with Mei's pipes and law; the bed load adds its sent planes, the next heights
             // and the talus, the godunov flux its faces' fluxes and slopes (48)
  return info;
}

PipeModel::PipeModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(PipeSettings::from(params)),
      dt_(settings_.dt_max),
      depth_(state_.field(kSurfaceWaterDepth)),
      flux_(state_.field(kSurfaceWaterOutflux)),
      velocity_(state_.field(kSurfaceWaterVelocity)),
      sediment_(state_.field(kSedimentSuspended)) {
  const std::size_t n = state_.vertices();
  auto& ctx = compute.context();
  previous_depth_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  compute.queue().enqueueFillBuffer(previous_depth_, 0.0f, 0, n * sizeof(float));
  capacity_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  cfl_speed2_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  sediment_next_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_long));
  sendable_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_int));
  if (!settings_.semi_lagrangian())
    sent_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(cl_int));
  stats_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * kStatBlocks * sizeof(float));
  outflow_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_long));
  lost_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_long));
  compute.queue().enqueueFillBuffer(outflow_, cl_long{0}, 0, sizeof(cl_long));
  compute.queue().enqueueFillBuffer(lost_, cl_long{0}, 0, sizeof(cl_long));
  const std::size_t edge_faces = 2 * static_cast<std::size_t>(terrain.nx + terrain.ny);
  edge_water_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, edge_faces * sizeof(cl_long));
  compute.queue().enqueueFillBuffer(edge_water_, cl_long{0}, 0, edge_faces * sizeof(cl_long));
  std::vector<std::string> sources = {"cl/common.cl", "cl/models/pipe.cl"};
  if (settings_.inertial()) sources.push_back("cl/models/pipe_inertial.cl");
  if (settings_.godunov()) sources.push_back("cl/models/pipe_godunov.cl");
  std::string options = settings_.build_options() + ground_defines(params);
  if (settings_.bedload()) {
    sources.push_back("cl/models/pipe_bedload.cl");
    options += SedimentSettings::from(params).build_options();
  }
  cl::Program& program = compute.program(sources, options);
  flux_kernel_ = Kernel(compute, program,
                        settings_.inertial()  ? "pipe_flux_inertial"
                        : settings_.godunov() ? "pipe_godunov_faces"
                                              : "pipe_flux");
  if (settings_.inertial()) {
    old_flux_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(float));
    flux_kernel_.set("old_flux", old_flux_);
  }
  water_kernel_ =
      Kernel(compute, program, settings_.godunov() ? "pipe_godunov_update" : "pipe_water");
  if (settings_.godunov()) {
    face_flux_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 8 * n * sizeof(float));
    slopes_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(float));
    slopes_kernel_ = Kernel(compute, program, "pipe_godunov_slopes");
    slopes_kernel_.set("slopes", slopes_).set("rain_weight", rain_weight());
    edge_before_ =
        cl::Buffer(ctx, CL_MEM_READ_WRITE,
                   3 * static_cast<std::size_t>(terrain.nx + terrain.ny) * sizeof(float));
    edges_kernel_ = Kernel(compute, program, "pipe_godunov_edges");
    edges_kernel_.set("face_flux", face_flux_).set("edge_before", edge_before_);
    edges_kernel_.set("rain_weight", rain_weight());
    water_kernel_.set("edge_before", edge_before_);
    for (Kernel* k : {&flux_kernel_, &water_kernel_})
      k->set("face_flux", face_flux_).set("slopes", slopes_);
  }
  erode_kernel_ = Kernel(compute, program, "pipe_erode");
  send_kernel_ = Kernel(compute, program, "pipe_send");
  receive_kernel_ = Kernel(compute, program, "pipe_receive");
  edge_outflow_kernel_ = Kernel(compute, program, "pipe_edge_outflow");
  advect_kernel_ = Kernel(compute, program, "pipe_advect");
  edge_water_kernel_ = Kernel(compute, program, "pipe_edge_water");
  stats_kernel_ = Kernel(compute, program, "pipe_stats");
  flux_kernel_.set("rain_weight", rain_weight());
  water_kernel_.set("rain_weight", rain_weight());
  bind_detachment(erode_kernel_, bed(), placeholder_);
  erode_kernel_.set("sendable", sendable_);
  if (settings_.bedload()) start_bed_load(compute, program, params);
  if (start_standing_water(params)) {
    // The first step must already respect the CFL limit of the standing water's waves.
    compute.queue().enqueueFillBuffer(cfl_speed2_, 0.0f, 0, n * sizeof(float));
    choose_next_dt();
  }
}

double PipeModel::scratch_bytes() const {
  return buffer_bytes({&previous_depth_, &capacity_, &cfl_speed2_, &sediment_next_, &sent_, &stats_,
                       &outflow_, &lost_, &edge_water_, &sendable_, &bed_sent_, &height_next_,
                       &bed_moved_, &old_flux_, &face_flux_, &slopes_, &edge_before_}) +
         (talus_ ? talus_->device_bytes() : 0.0);
}

double PipeModel::take_step() {
  DeviceTerrain& terrain = state_.terrain();
  const int nx = terrain.nx(), ny = terrain.ny(), n = nx * ny;
  const float q = static_cast<float>(terrain.quantum()), cell = terrain.cell(),
              dt = static_cast<float>(dt_);
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  cl::Buffer &depth = state_.buffer(depth_), &flux = state_.buffer(flux_),
             &velocity = state_.buffer(velocity_), &sediment = state_.buffer(sediment_);
  const cl_ulong seed = static_cast<cl_ulong>(params_.integer("run.seed")), step = steps();
  for (Kernel* k : {&flux_kernel_, &water_kernel_, &erode_kernel_}) {
    k->set("nx", nx).set("ny", ny);
    if (k->has("cell")) k->set("cell", cell);
    if (k->has("dt")) k->set("dt", dt);
    if (k->has("quantum")) k->set("quantum", q);
  }
  flux_kernel_.set("height_view", terrain.height()).set("depth", depth);
  if (flux_kernel_.has("flux")) flux_kernel_.set("flux", flux);
  if (flux_kernel_.has("velocity")) flux_kernel_.set("velocity", velocity);
  if (settings_.inertial())  // every cell reads its neighbours' outflows as the step began
    compute_.queue().enqueueCopyBuffer(flux, old_flux_, 0, 0,
                                       4 * static_cast<std::size_t>(n) * sizeof(float));
  flux_kernel_.set("rain_on", rain_on());
  water_kernel_.set("rain_on", rain_on());
  water_kernel_.set("depth", depth).set("flux", flux).set("velocity", velocity);
  water_kernel_.set("previous_depth", previous_depth_).set("capacity", capacity_);
  water_kernel_.set("cfl_speed2", cfl_speed2_);
  water_kernel_.set("evaporation_factor",
                    static_cast<float>(std::exp(-settings_.evaporation * dt_)));
  water_kernel_.set("height_view", terrain.height());
  erode_kernel_.set("height", terrain.height_fixed()).set("capacity_of_cell", capacity_);
  erode_kernel_.set("sediment", sediment);
  erode_kernel_.set("key", static_cast<cl_ulong>(rng_key(seed, kPipeErodeStream, step)));
  // The exact relaxation over the step, whatever Δt (models.md "pipe").
  erode_kernel_
      .set("dissolved_fraction", static_cast<float>(-std::expm1(-settings_.dissolve * dt_)))
      .set("deposited_fraction", static_cast<float>(-std::expm1(-settings_.deposit * dt_)));
  if (settings_.godunov()) {
    slopes_kernel_.set("height_view", terrain.height())
        .set("depth", depth)
        .set("nx", nx)
        .set("ny", ny);
    slopes_kernel_.set("dt", dt).set("rain_on", rain_on()).launch(work);
    edges_kernel_.set("depth", depth).set("velocity", velocity).set("nx", nx).set("ny", ny);
    edges_kernel_.set("dt", dt).set("rain_on", rain_on());
  }
  // The water's flux, then (godunov) the map's edge faces over it, then the cells' water.
  const auto move_water = [&] {
    flux_kernel_.launch(work);
    if (settings_.godunov())
      edges_kernel_.launch(round_up_work(2 * static_cast<std::size_t>(nx + ny)));
    water_kernel_.launch(work);
  };
  if (settings_.bedload()) {
    move_water();
    count_edge_water(flux, dt);
    move_bed_load(depth, flux, dt);
  } else {
    move_water();
    erode_kernel_.launch(work);
    count_edge_water(flux, dt);
    transport(sediment, flux, velocity, dt);
    std::swap(sediment, sediment_next_);  // the state's field now holds the transported sediment
  }
  terrain.apply();
  if (settings_.bedload()) relax_talus(dt_);
  const double taken = dt_;
  choose_next_dt();
  return taken;
}

// Moves the suspended sediment into sediment_next_: with the water that leaves each cell, or by
// semi-Lagrangian advection (the documented non-conserving option).
void PipeModel::transport(cl::Buffer& sediment, cl::Buffer& flux, cl::Buffer& velocity, float dt) {
  const int nx = state_.terrain().nx(), ny = state_.terrain().ny(), n = nx * ny;
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  if (settings_.semi_lagrangian()) {
    advect_kernel_.set("sediment", sediment)
        .set("sediment_next", sediment_next_)
        .set("velocity", velocity);
    advect_kernel_.set("nx", nx).set("ny", ny).set("cell", state_.terrain().cell()).set("dt", dt);
    advect_kernel_.set("lost", lost_).launch(work);
    return;
  }
  send_kernel_.set("sendable", sendable_).set("flux", flux).set("previous_depth", previous_depth_);
  send_kernel_.set("sent", sent_)
      .set("nx", nx)
      .set("ny", ny)
      .set("cell", state_.terrain().cell())
      .set("dt", dt);
  const auto seed = static_cast<std::uint64_t>(params_.integer("run.seed"));
  send_kernel_.set("key", static_cast<cl_ulong>(rng_key(seed, kPipeTransportStream, steps())));
  send_kernel_.launch(work);
  receive_kernel_.set("sediment", sediment).set("sediment_next", sediment_next_).set("sent", sent_);
  receive_kernel_.set("nx", nx).set("ny", ny).launch(work);
  edge_outflow_kernel_.set("sent", sent_).set("nx", nx).set("ny", ny).set("outflow", outflow_);
  edge_outflow_kernel_.launch(round_up_work(2 * static_cast<std::size_t>(nx + ny)));
}

// The water each edge face let out this step (the pipes' outflows there, as the water pass used
// them).
void PipeModel::count_edge_water(cl::Buffer& flux, float dt) {
  const int nx = state_.terrain().nx(), ny = state_.terrain().ny();
  edge_water_kernel_.set("flux", flux).set("nx", nx).set("ny", ny).set("dt", dt);
  edge_water_kernel_.set("water_quantum", static_cast<float>(water_count_volume()));
  edge_water_kernel_.set("edge_water", edge_water_);
  edge_water_kernel_.launch(round_up_work(2 * static_cast<std::size_t>(nx + ny)));
}

double PipeModel::water_count_volume() const {
  const double cell = state_.initial_terrain().cell;
  return kPipeWaterCountDepth * cell * cell;
}

namespace {
// Which edge (kEdgeNames' order) face f of pipe_edge_water is: the rows' west and east faces
// alternate, then the columns' north and south faces.
int edge_of_face(std::size_t f, int ny) {
  return f < 2 * static_cast<std::size_t>(ny) ? static_cast<int>(f & 1)
                                              : 2 + static_cast<int>(f & 1);
}
const char* const kEdgeWaterCounters[4] = {"water_out_west", "water_out_east", "water_out_north",
                                           "water_out_south"};
}  // namespace

std::array<long long, 4> PipeModel::edge_water_counts() {
  const int ny = state_.terrain().ny();
  std::vector<cl_long> faces(2 * static_cast<std::size_t>(state_.terrain().nx() + ny));
  compute_.queue().enqueueReadBuffer(edge_water_, CL_TRUE, 0, faces.size() * sizeof(cl_long),
                                     faces.data());
  std::array<long long, 4> counts{};
  for (std::size_t f = 0; f < faces.size(); ++f) counts[edge_of_face(f, ny)] += faces[f];
  return counts;
}

std::array<double, 4> PipeModel::edge_water_outflow() {
  const std::array<long long, 4> counts = edge_water_counts();
  std::array<double, 4> volumes{};
  for (int e = 0; e < 4; ++e) volumes[e] = static_cast<double>(counts[e]) * water_count_volume();
  return volumes;
}

// The next step: the CFL limit of the shallow-water waves and the flow (Fritz 2016 saw oscillation
// and overflow with steps that violate it).
void PipeModel::choose_next_dt() {
  const int n = static_cast<int>(state_.vertices());
  const int chunk = (n + kStatBlocks - 1) / kStatBlocks;
  // The depth and the speeds the CFL limit counts, as pipe_water left them in the step just taken.
  stats_kernel_.set("depth", state_.buffer(depth_))
      .set("cfl_speed2", cfl_speed2_)
      .set("nx", state_.terrain().nx())
      .set("ny", state_.terrain().ny())
      .set("chunk", chunk)
      .set("stats", stats_)
      .launch(kStatBlocks);
  std::vector<float> stats(4 * kStatBlocks);
  compute_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, stats.size() * sizeof(float),
                                     stats.data());
  double d_max = 0, v_max = 0, discharge = 0, discharge_froude = 0;
  for (int b = 0; b < kStatBlocks; ++b) {
    d_max = std::max(d_max, static_cast<double>(stats[4 * b]));
    v_max = std::max(v_max, static_cast<double>(stats[4 * b + 1]));
    discharge += stats[4 * b + 2];
    discharge_froude += stats[4 * b + 3];
  }
  const double froude = discharge > 0 ? discharge_froude / discharge : 0.0;
  if (std::isfinite(froude))
    flow_froude_max_micro_ =
        std::max(flow_froude_max_micro_, static_cast<std::int64_t>(std::llround(froude * 1e6)));
  if (!std::isfinite(d_max) || !std::isfinite(v_max)) {
    throw runtime_error("pipe model at t = " + format_number(time() + dt_) +
                        " s: water depth or velocity is not finite");
  }
  dt_ = std::min(settings_.dt_max, settings_.cfl * state_.terrain().cell() /
                                       (std::sqrt(settings_.gravity * d_max) + v_max + 1e-9));
  if (dt_ < settings_.dt_min) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "pipe model at step %llu, t = %.6g s: the time step collapsed to %.3g s "
                  "(pipe.dt_min %.3g s; depth up to %.3g m, speed up to %.3g m/s)",
                  static_cast<unsigned long long>(steps() + 1), time() + dt_, dt_, settings_.dt_min,
                  d_max, v_max);
    throw runtime_error(buf);
  }
}

long long PipeModel::outflow_quanta() {
  cl_long v = 0;
  compute_.queue().enqueueReadBuffer(outflow_, CL_TRUE, 0, sizeof(v), &v);
  return v;
}

long long PipeModel::lost_quanta() {
  cl_long v = 0;
  compute_.queue().enqueueReadBuffer(lost_, CL_TRUE, 0, sizeof(v), &v);
  return v;
}

std::vector<std::pair<std::string, std::int64_t>> PipeModel::counters() {
  std::vector<std::pair<std::string, std::int64_t>> c = {{"outflow_quanta", outflow_quanta()},
                                                         {"lost_quanta", lost_quanta()}};
  if (settings_.bedload()) c.emplace_back("bed_moved_quanta", bed_moved_quanta());
  const std::array<long long, 4> out = edge_water_counts();
  for (int e = 0; e < 4; ++e) c.emplace_back(kEdgeWaterCounters[e], out[e]);
  c.emplace_back("flow_froude_max_micro", flow_froude_max_micro_);
  return c;
}

void PipeModel::restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) {
  const cl_long outflow = counter_value(c, "outflow_quanta"),
                lost = counter_value(c, "lost_quanta");
  compute_.queue().enqueueWriteBuffer(outflow_, CL_TRUE, 0, sizeof(outflow), &outflow);
  compute_.queue().enqueueWriteBuffer(lost_, CL_TRUE, 0, sizeof(lost), &lost);
  // Each edge's total goes to one of its faces: only the sums are ever read. (A file written
  // before the water was counted continues from none.)
  const int ny = state_.terrain().ny();
  std::vector<cl_long> faces(2 * static_cast<std::size_t>(state_.terrain().nx() + ny), 0);
  const std::size_t first_face[4] = {0, 1, 2 * static_cast<std::size_t>(ny),
                                     2 * static_cast<std::size_t>(ny) + 1};
  for (int e = 0; e < 4; ++e) faces[first_face[e]] = counter_value_or(c, kEdgeWaterCounters[e], 0);
  compute_.queue().enqueueWriteBuffer(edge_water_, CL_TRUE, 0, faces.size() * sizeof(cl_long),
                                      faces.data());
  flow_froude_max_micro_ = counter_value_or(c, "flow_froude_max_micro", 0);
  if (settings_.bedload()) {
    const cl_long moved = counter_value(c, "bed_moved_quanta");
    compute_.queue().enqueueWriteBuffer(bed_moved_, CL_TRUE, 0, sizeof(moved), &moved);
  }
}

double PipeModel::rain_volume() {
  return scenario_rain_volume() + painted_volume_;
}

JsonObject PipeModel::diagnostics() {
  return JsonObject()
      .add("next_dt_s", dt_)
      .add("water_volume_m3", water_volume())
      .add("initial_water_volume_m3", initial_water_volume())
      .add("law", settings_.law)
      .add("flux", settings_.flux)
      .add("flow_froude_max", flow_froude_max())
      .add("bed_load_moved_m3",
           static_cast<double>(bed_moved_quanta()) * state_.terrain().volume_quantum())
      .add("edges", settings_.edges)
      .add("transport", settings_.transport);
}

std::vector<std::pair<std::string, double>> PipeModel::summary_values() {
  return {{model_info().summary_names[0], flow_froude_max()}};
}

// Without the advection term the local-inertial equations carry a disturbance of a sheet under
// Manning's friction at sqrt(g h) against the kinematic wave's (5/3) u: above Froude 3/5 the
// kinematic wave outruns the dynamic waves and grows into roll waves (Whitham's criterion; the
// full shallow-water equations hold to Froude 3/2). docs/models.md derives it.
std::string PipeModel::caution() {
  constexpr double kInertialFroudeLimit = 0.6;
  if (!settings_.inertial() || flow_froude_max() <= kInertialFroudeLimit) return {};
  char line[400];
  std::snprintf(
      line, sizeof line,
      "pipe.flux = \"local-inertial\": the flow reached Froude %.2f (its discharge-weighted "
      "mean; metrics.json: flow_froude_max), where its equations, without advection, let a "
      "sheet's disturbances grow into roll waves (they hold a sheet steady only below Froude "
      "0.6 under Manning's friction; docs/models.md); "
      "pipe.flux = \"godunov\" carries such flow",
      flow_froude_max());
  return line;
}

}  // namespace runnel
