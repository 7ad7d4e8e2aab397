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
// (/height, frames × ny × nx) and each terrain frame's surface and fields (/terrain/STEP/: its
// points in the map frame, height, Δh and the water's depth, speed and velocity where the model
// has water), SPH particle snapshots every `particle_every` steps (/particles/STEP/...), the
// frames' steps and times, the grid's map coordinates and quads; and series.xmf, the XDMF index
// ParaView (its XDMF3 and legacy readers) and VisIt open as a time series of a terrain surface and
// a particle cloud; and series.pvd with series_vtk/, the same frames as VTK files, which ParaView
// opens as two named blocks (terrain, particles). The first frame is the state the run starts from
// and the last its end, whatever the interval. Written as series.h5.partial during the run, renamed
// when it ends.
class SeriesWriter {
 public:
  SeriesWriter(const std::filesystem::path& out, long long height_every, long long particle_every,
               const Heightmap& initial);
  ~SeriesWriter();
  bool active() const { return file_ != nullptr; }
  // The frames of the state the run starts from (t = 0, or where it resumes).
  void start(Model& model);
  // Appends the frames due after the model's latest step.
  void after_step(Model& model);
  // The frames of the final state (unless the interval just wrote them), the frame tables; renames
  // series.h5.partial to series.h5 and writes series.xmf.
  void finish(Model& model);
  // A run that stopped on a failure: the frames written so far become series.h5 (no frame of the
  // failed state is added); when a frame's write failed (a full disk) or the index cannot be
  // written, the partial file is removed instead.
  void keep_written() noexcept;

 private:
  struct Frame {
    std::uint64_t step;
    double time;
    std::size_t count;  // particles (particle frames)
  };
  void write_terrain(Model& model);
  void write_particles(Model& model);
  void write_terrain_vtk(std::uint64_t step, const std::vector<double>& points,
                         const std::vector<float>& height, const std::vector<float>& change,
                         const WaterView& water, const std::vector<float>& velocity) const;
  void write_xdmf() const;
  void write_pvd() const;
  void publish();
  // The terrain frame's fields beyond the height: which the model has (the same every frame).
  bool has_water_depth_ = false, has_speed_ = false, has_velocity_ = false;
  std::filesystem::path out_;
  long long height_every_, particle_every_;
  Heightmap grid_;  // the initial terrain: the grid and its georeferencing
  std::unique_ptr<H5File> file_;
  bool broken_ = false;  // a frame's write failed: keep_written() removes the file
  std::vector<Frame> height_frames_, particle_frames_;
};

}  // namespace runnel
