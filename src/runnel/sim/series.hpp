// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/model.hpp"

namespace runnel {

// A run's time series (docs/series.md): series.h5 with the heightmap every `height_every` steps
// (/height, frames × ny × nx, as before) and SPH particle snapshots every `particle_every` steps
// (/particles/STEP/...), the frames' steps and times, the grid's map coordinates and quads; and
// series.xmf, the XDMF index ParaView and VisIt open as a time series of a terrain surface and a
// particle cloud. Written as series.h5.partial during the run, renamed when it ends.
class SeriesWriter {
 public:
  SeriesWriter(const std::filesystem::path& out, long long height_every, long long particle_every,
               const Heightmap& initial);
  ~SeriesWriter();
  bool active() const { return file_ != nullptr; }
  // Appends the frames due after the model's latest step.
  void after_step(Model& model);
  // Writes the frame tables, renames series.h5.partial to series.h5 and writes series.xmf.
  void finish();

 private:
  struct Frame {
    std::uint64_t step;
    double time;
    std::size_t count;  // particles (particle frames)
  };
  void write_particles(const CheckpointData& d, std::uint64_t step);
  void write_xdmf() const;
  std::filesystem::path out_;
  long long height_every_, particle_every_;
  Heightmap grid_;  // the initial terrain: the grid and its georeferencing
  std::unique_ptr<H5File> file_;
  std::vector<Frame> height_frames_, particle_frames_;
};

// A checkpoint's SPH particles as a binary PLY file (splashsurf, ParaView, MeshLab): positions in
// the map frame (double), velocity, density, sediment, age and the stable id per vertex.
void write_particles_ply(const std::string& path, const CheckpointData& data);

}  // namespace runnel
