// SPDX-License-Identifier: MIT
// Host side of cl/models/pipe_bedload.cl: the pipe model's bed-load law (pipe.law = "bedload").
#include "runnel/compute/launch.hpp"
#include "runnel/core/clock.hpp"
#include "runnel/core/rng.hpp"
#include "runnel/ground/bedload.hpp"
#include "runnel/models/pipe_model.hpp"

namespace runnel {

void PipeModel::start_bed_load(ComputeContext& compute, cl::Program& program,
                               const Parameters& params) {
  const std::size_t n = state_.vertices();
  auto& ctx = compute.context();
  bed_sent_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(cl_int));
  height_next_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_long));
  bed_moved_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_long));
  compute.queue().enqueueFillBuffer(bed_moved_, cl_long{0}, 0, sizeof(cl_long));
  bedload_kernel_ = Kernel(compute, program, "pipe_bedload");
  bind_detachment(bedload_kernel_, bed(), placeholder_);
  const ThermalSettings thermal = ThermalSettings::from(params);
  talus_interval_ = thermal.interval;
  if (talus_interval_ > 0)
    talus_ = std::make_unique<ThermalRelaxation>(compute, state_.terrain(), thermal, bed());
}

void PipeModel::move_bed_load(cl::Buffer& depth, cl::Buffer& flux, float dt) {
  DeviceTerrain& terrain = state_.terrain();
  const int nx = terrain.nx(), ny = terrain.ny(), n = nx * ny;
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  const auto seed = static_cast<std::uint64_t>(params_.integer("run.seed"));
  bedload_kernel_.set("depth", depth).set("flux", flux).set("sent", bed_sent_);
  bedload_kernel_.set("nx", nx).set("ny", ny).set("cell", terrain.cell()).set("dt", dt);
  bedload_kernel_.set("quantum", static_cast<float>(terrain.quantum()));
  bedload_kernel_.set("key", static_cast<cl_ulong>(rng_key(seed, kPipeBedloadStream, steps())));
  bedload_kernel_.set("moved", bed_moved_).launch(work);
  // The bed's heights move as the suspended load does: out through the faces, in from the
  // neighbours, off the map at the open edges.
  receive_kernel_.set("sediment", terrain.height_fixed())
      .set("sediment_next", height_next_)
      .set("sent", bed_sent_);
  receive_kernel_.set("nx", nx).set("ny", ny).launch(work);
  compute_.queue().enqueueCopyBuffer(height_next_, terrain.height_fixed(), 0, 0,
                                     static_cast<std::size_t>(n) * sizeof(cl_long));
  edge_outflow_kernel_.set("sent", bed_sent_).set("nx", nx).set("ny", ny).set("outflow", outflow_);
  edge_outflow_kernel_.launch(round_up_work(2 * static_cast<std::size_t>(nx + ny)));
}

// Slopes steeper than the (submerged) angle of repose slide, every thermal.interval seconds of
// the run's clock, so a resumed run relaxes when the uninterrupted one did.
void PipeModel::relax_talus(double dt) {
  if (talus_ && interval_credit(talus_interval_, time(), dt) > 0) talus_->relax();
}

long long PipeModel::bed_moved_quanta() {
  if (!settings_.bedload()) return 0;
  cl_long v = 0;
  compute_.queue().enqueueReadBuffer(bed_moved_, CL_TRUE, 0, sizeof(v), &v);
  return v;
}

}  // namespace runnel
