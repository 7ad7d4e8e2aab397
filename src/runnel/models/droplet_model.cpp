// SPDX-License-Identifier: MIT
#include "runnel/models/droplet_model.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"

namespace runnel {

DropletSettings DropletSettings::from(const Parameters& p) {
  DropletSettings s;
  s.radius = p.real("droplet.radius");
  s.inertia = p.real("droplet.inertia");
  s.capacity = p.real("droplet.capacity");
  s.min_capacity = p.real("droplet.min_capacity");
  s.erode = p.real("droplet.erode");
  s.deposit = p.real("droplet.deposit");
  s.evaporate = p.real("droplet.evaporate");
  s.gravity = p.real("droplet.gravity");
  s.lifetime = static_cast<int>(p.integer("droplet.lifetime"));
  s.initial_water = p.real("droplet.initial_water");
  s.initial_speed = p.real("droplet.initial_speed");
  s.batch = p.integer("droplet.batch");
  return s;
}

std::string DropletSettings::build_options() const {
  std::string o;
  o += float_define("DROPLET_RADIUS", radius);
  o += float_define("DROPLET_INERTIA", inertia);
  o += float_define("DROPLET_CAPACITY", capacity);
  o += float_define("DROPLET_MIN_CAPACITY", min_capacity);
  o += float_define("DROPLET_ERODE", erode);
  o += float_define("DROPLET_DEPOSIT", deposit);
  o += float_define("DROPLET_EVAPORATE", evaporate);
  o += float_define("DROPLET_GRAVITY", gravity);
  o += float_define("DROPLET_INITIAL_WATER", initial_water);
  o += float_define("DROPLET_INITIAL_SPEED", initial_speed);
  o += " -DDROPLET_LIFETIME=" + std::to_string(lifetime);
  o += " -DDROPLET_RADIUS_CELLS=" + std::to_string(static_cast<int>(std::ceil(radius)));
  return o;
}

DropletModel::DropletModel(ComputeContext& compute, DeviceTerrain& terrain,
                           const DropletSettings& settings, std::uint64_t seed)
    : compute_(compute),
      terrain_(terrain),
      settings_(settings),
      seed_(seed),
      kernel_(compute.program({"cl/common.cl", "cl/models/droplet.cl"}, settings.build_options()),
              "droplet_batch"),
      counters_(compute.context(), CL_MEM_READ_WRITE, 2 * sizeof(cl_long)) {
  const cl_long zero = 0;
  compute.queue().enqueueFillBuffer(counters_, zero, 0, 2 * sizeof(cl_long));
}

void DropletModel::advance() {
  // Droplets of one batch do not see each other's changes: many ending in the same pit would all
  // fill it. One droplet per 64 cells by default keeps that rare.
  const long long automatic =
      std::max<long long>(1, static_cast<long long>(terrain_.nx()) * terrain_.ny() / 64);
  const cl_uint count = static_cast<cl_uint>(settings_.batch > 0 ? settings_.batch : automatic);
  set_args(kernel_, terrain_.height(), terrain_.delta(), terrain_.nx(), terrain_.ny(),
           static_cast<float>(terrain_.quantum()), static_cast<cl_ulong>(seed_),
           static_cast<cl_ulong>(droplets_), count, counters_);
  compute_.profiler().launch(kernel_, round_up_work(count), "droplet_batch");
  terrain_.apply();
  droplets_ += count;
}

long long DropletModel::outflow_quanta() {
  cl_long c[2];
  compute_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c);
  return c[1];
}

long long DropletModel::droplets_out() {
  cl_long c[2];
  compute_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c);
  return c[0];
}

}  // namespace runnel
