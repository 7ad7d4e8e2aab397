// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"

namespace runnel {

// Gauges ([[probes]]): points in map metres where a run records the water surface, the water depth
// and the bed every run.probe_every of its clock, into probes.csv (docs/guide.md, "Gauges").

struct Probe {
  std::string name;
  double x = 0, z = 0;  // world metres from the terrain's first vertex (x east, z south)
};

// The scenario's probes on `terrain`. Throws an input error naming the probe when its name is
// empty, repeated or not a plain word (letters, digits, _ and -), or when it lies off the terrain.
std::vector<Probe> probes_of(const Parameters& params, const Heightmap& terrain);

// What a gauge reads: the bed (m) and the water depth (m) at the point, each interpolated on the
// terrain's triangles (surface_height's split), and the water surface, bed + depth.
struct ProbeReading {
  double surface = 0, depth = 0, bed = 0;
};
ProbeReading read_probe(const Heightmap& bed, const std::vector<float>& depth, const Probe& probe);

// The rows of probes.csv: one per probe every `every` (clock units) from t = 0, at the first step
// that reaches each sampling time.
class ProbeRecorder {
 public:
  ProbeRecorder(std::vector<Probe> probes, double every);
  bool active() const { return !probes_.empty() && every_ > 0; }
  // Whether a sample is due at clock time `t`.
  bool due(double t) const { return active() && t >= (taken_ - 1e-9) * every_; }
  void record(double t, const Heightmap& bed, const std::vector<float>& depth);
  // "t,name,surface,depth,bed\n" and the rows so far.
  std::string csv() const;
  std::size_t rows() const { return rows_; }

 private:
  std::vector<Probe> probes_;
  double every_ = 0;
  long long taken_ = 0;  // sampling times passed: the next is taken_ · every_
  std::string text_;
  std::size_t rows_ = 0;
};

}  // namespace runnel
