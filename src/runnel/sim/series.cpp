// SPDX-License-Identifier: MIT
#include "runnel/sim/series.hpp"

#include <bit>
#include <cstdio>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/georeference_h5.hpp"
#include "runnel/io/vtk_xml.hpp"
#include "runnel/sim/particle_export.hpp"
#include "runnel/sph/particle_store.hpp"

namespace runnel {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPartial = "series.h5.partial";
constexpr const char* kVtkFolder = "series_vtk";  // the frames as VTK files, indexed by series.pvd

std::string step_name(std::uint64_t step) {
  char name[32];
  std::snprintf(name, sizeof name, "%010llu", static_cast<unsigned long long>(step));
  return name;
}

// An HDF5 data item of series.h5 in XDMF.
std::string hdf_item(const std::string& dims, const char* type, int precision,
                     const std::string& path) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"" +
         std::to_string(precision) + "\" Format=\"HDF\">series.h5:" + path + "</DataItem>";
}

}  // namespace

SeriesWriter::SeriesWriter(const fs::path& out, long long height_every, long long particle_every,
                           const Heightmap& initial)
    : out_(out), height_every_(height_every), particle_every_(particle_every), grid_(initial) {
  if (height_every_ <= 0 && particle_every_ <= 0) return;
  file_ = std::make_unique<H5File>(H5File::create((out_ / kPartial).string()));
  file_->attribute("/", "series_every_steps", static_cast<std::int64_t>(height_every_));
  file_->attribute("/", "particles_every_steps", static_cast<std::int64_t>(particle_every_));
  // The grid in the map frame (double: map coordinates can be millions of metres), and its quads.
  const MapFrame map(grid_);
  const std::size_t nx = static_cast<std::size_t>(grid_.nx),
                    ny = static_cast<std::size_t>(grid_.ny);
  std::vector<double> x(nx * ny), y(nx * ny);
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx; ++i) {
      x[j * nx + i] = map.x(static_cast<double>(i) * grid_.cell);
      y[j * nx + i] = map.y(static_cast<double>(j) * grid_.cell);
    }
  }
  std::vector<std::int32_t> quads;
  quads.reserve(4 * (nx - 1) * (ny - 1));
  for (std::size_t j = 0; j + 1 < ny; ++j) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      const auto k = static_cast<std::int32_t>(j * nx + i), w = static_cast<std::int32_t>(nx);
      for (std::int32_t v : {k, k + 1, k + w + 1, k + w}) quads.push_back(v);
    }
  }
  file_->create_group("/grid");
  file_->write("/grid/x", x, {ny, nx});
  file_->write("/grid/y", y, {ny, nx});
  file_->write("/grid/quads", quads, {(nx - 1) * (ny - 1), 4});
  write_georeference(*file_, "/grid", grid_);
  file_->create_group("/particles");
  file_->create_group("/terrain");
  // The frames' folder: never written through a link (the output folder's rule for checkpoints/).
  if (fs::is_symlink(out_ / kVtkFolder))
    throw input_error(
        "--out " + out_.string() + ": " + kVtkFolder +
        " is a link; runnel neither writes nor removes through it (choose another --out)");
  fs::create_directories(out_ / kVtkFolder);
}

SeriesWriter::~SeriesWriter() = default;

void SeriesWriter::start(Model& model) {
  if (!file_) return;
  try {
    file_->attribute("/", "time_units", std::string(time_units(model.info().clock)));
    if (height_every_ > 0) write_terrain(model);
    if (particle_every_ > 0) write_particles(model);
  } catch (...) {
    broken_ = true;  // the first frame half written (a full disk): the file is removed now, as
    keep_written();  // the run stops before its steps, where a failed run keeps what it wrote
    throw;
  }
}

void SeriesWriter::after_step(Model& model) {
  if (!file_) return;
  const std::uint64_t step = model.steps();
  try {
    if (height_every_ > 0 && step % static_cast<std::uint64_t>(height_every_) == 0)
      write_terrain(model);
    if (particle_every_ > 0 && step % static_cast<std::uint64_t>(particle_every_) == 0)
      write_particles(model);
  } catch (...) {
    broken_ = true;  // a frame half written (a full disk): the file is not kept
    throw;
  }
}

void SeriesWriter::write_terrain(Model& model) {
  const std::uint64_t step = model.steps();
  const Heightmap t = model.terrain();
  const Heightmap reference = model.erosion_reference();
  file_->append_frame("/height", t.h, t.ny, t.nx);
  height_frames_.push_back({step, model.time(), 0});
  // The frame's own surface and fields: what ParaView's XDMF3 reader reads (it skips hyperslabs
  // and X_Y_Z geometries, so the surface's points are stored whole, in the map frame).
  const std::string group = "/terrain/" + step_name(step);
  const auto nx = static_cast<std::size_t>(t.nx), ny = static_cast<std::size_t>(t.ny);
  const MapFrame map(t);
  std::vector<double> points(3 * nx * ny);
  std::vector<float> change(nx * ny);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const std::size_t k = j * nx + i;
      points[3 * k] = map.x(static_cast<double>(i) * t.cell);
      points[3 * k + 1] = map.y(static_cast<double>(j) * t.cell);
      points[3 * k + 2] = t.h[k];
      change[k] = t.h[k] - reference.h[k];
    }
  file_->create_group(group);
  file_->attribute(group, "time", model.time());
  file_->write(group + "/points", points, {nx * ny, 3});
  file_->write(group + "/height", t.h, {ny, nx});
  file_->write(group + "/dh", change, {ny, nx});
  const WaterView water = model.interaction().water_view();
  has_water_depth_ = !water.depth.empty();
  has_speed_ = !water.speed.empty();
  if (has_water_depth_) file_->write(group + "/depth", water.depth, {ny, nx});
  if (has_speed_) file_->write(group + "/speed", water.speed, {ny, nx});
  has_velocity_ = !water.velocity.empty();
  std::vector<float> velocity;  // the water's (x east, z south) → the map frame's (east, north, up)
  if (has_velocity_) {
    velocity.assign(3 * nx * ny, 0.0f);
    for (std::size_t k = 0; k < nx * ny; ++k) {
      velocity[3 * k] = water.velocity[2 * k];
      velocity[3 * k + 1] = -water.velocity[2 * k + 1];
    }
    file_->write(group + "/velocity", velocity, {nx * ny, 3});
  }
  write_terrain_vtk(step, points, t.h, change, water, velocity);
}

// The terrain frame as VTK's structured grid (series_vtk/terrain_STEP.vts): the surface's points
// and the frame's fields, for series.pvd.
void SeriesWriter::write_terrain_vtk(std::uint64_t step, const std::vector<double>& points,
                                     const std::vector<float>& height,
                                     const std::vector<float>& change, const WaterView& water,
                                     const std::vector<float>& velocity) const {
  const std::size_t n = height.size();
  std::vector<VtkArray> fields = {{"height", "Float32", 1, height.data(), n * sizeof(float)},
                                  {"dh", "Float32", 1, change.data(), n * sizeof(float)}};
  if (has_water_depth_)
    fields.push_back({"depth", "Float32", 1, water.depth.data(), n * sizeof(float)});
  if (has_speed_) fields.push_back({"speed", "Float32", 1, water.speed.data(), n * sizeof(float)});
  if (has_velocity_)
    fields.push_back({"velocity", "Float32", 3, velocity.data(), velocity.size() * sizeof(float)});
  const std::string extent =
      "0 " + std::to_string(grid_.nx - 1) + " 0 " + std::to_string(grid_.ny - 1) + " 0 0";
  write_vtk_xml(
      (out_ / kVtkFolder / ("terrain_" + step_name(step) + ".vts")).string(), "StructuredGrid",
      "WholeExtent=\"" + extent + "\"", "Extent=\"" + extent + "\"",
      {{"PointData", "Scalars=\"height\"", fields},
       {"Points", "", {{"Points", "Float64", 3, points.data(), points.size() * sizeof(double)}}}});
}

void SeriesWriter::write_particles(Model& model) {
  const CheckpointData d = model.checkpoint();
  const std::uint64_t step = model.steps();
  particle_frames_.push_back({step, model.time(), d.particles.size()});
  const HostParticles& p = d.particles;
  const std::size_t n = p.size();
  const MapParticles m = map_particles(p, grid_);
  const std::string group = "/particles/" + step_name(step);
  file_->create_group(group);
  file_->attribute(group, "time", d.time);
  file_->write(group + "/position", m.position, {n, 3});
  file_->write(group + "/velocity", m.velocity, {n, 3});
  file_->write(group + "/density", p.f[kRho], {n});
  file_->write(group + "/sediment", p.sediment, {n});
  file_->write(group + "/age", p.f[kAge], {n});
  file_->write(group + "/id", m.id, {n});
  // Each particle a vertex cell of its own: without the list ParaView's default XDMF3 reader reads
  // the points and no cells, and draws nothing.
  std::vector<std::uint32_t> vertices(n);
  for (std::size_t k = 0; k < n; ++k) vertices[k] = static_cast<std::uint32_t>(k);
  file_->write(group + "/vertices", vertices, {n});
  write_particles_vtp((out_ / kVtkFolder / ("particles_" + step_name(step) + ".vtp")).string(), p,
                      m);
}

void SeriesWriter::finish(Model& model) {
  if (!file_) return;
  if (height_every_ > 0 && (height_frames_.empty() || height_frames_.back().step != model.steps()))
    write_terrain(model);
  if (particle_every_ > 0 &&
      (particle_frames_.empty() || particle_frames_.back().step != model.steps()))
    write_particles(model);
  publish();
}

// The frames' index, then the file under its final name with its XDMF index beside it.
void SeriesWriter::publish() {
  for (auto [frames, name] :
       {std::pair{&height_frames_, "height"}, std::pair{&particle_frames_, "particle"}}) {
    std::vector<double> time;
    std::vector<std::int64_t> step;
    for (const Frame& f : *frames) {
      time.push_back(f.time);
      step.push_back(static_cast<std::int64_t>(f.step));
    }
    file_->write(std::string("/") + name + "_time", time, {time.size()});
    file_->write(std::string("/") + name + "_step", step, {step.size()});
  }
  file_.reset();
  write_path_atomically((out_ / "series.h5").string(), [&](const std::string& temporary) {
    fs::rename(out_ / kPartial, temporary);
  });
  write_xdmf();
  write_pvd();
}

// series.pvd: the VTK frames as one time series of two named blocks, terrain and particles, as
// ParaView's PVD reader shows them (its default XDMF3 reader gives series.xmf's two grids as
// unnamed pieces of one block).
void SeriesWriter::write_pvd() const {
  std::string x =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  const auto entry = [&](const Frame& f, int part, const char* name, const char* extension) {
    char time[64];
    std::snprintf(time, sizeof time, "%.17g", f.time);
    x += "<DataSet timestep=\"" + std::string(time) + "\" part=\"" + std::to_string(part) +
         "\" name=\"" + name + "\" file=\"" + kVtkFolder + "/" + name + "_" + step_name(f.step) +
         extension + "\"/>\n";
  };
  for (const Frame& f : height_frames_) entry(f, 0, "terrain", ".vts");
  // Every particle frame, empty ones too: the reader builds its blocks from the parts it finds at
  // a time, and a part that appears later would not be shown.
  for (const Frame& f : particle_frames_) entry(f, 1, "particles", ".vtp");
  x += "</Collection>\n</VTKFile>\n";
  write_text_atomically((out_ / "series.pvd").string(), x);
}

void SeriesWriter::keep_written() noexcept {
  if (!file_) return;
  if (!broken_) {
    try {
      publish();
      return;
    } catch (...) {
    }
  }
  file_.reset();
  std::error_code ec;
  fs::remove(out_ / kPartial, ec);
}

void SeriesWriter::write_xdmf() const {
  const std::string ny = std::to_string(grid_.ny), nx = std::to_string(grid_.nx);
  const std::string grid = ny + " " + nx;
  const std::string quads = std::to_string(static_cast<long long>(grid_.nx - 1) * (grid_.ny - 1));
  const std::string frames = std::to_string(height_frames_.size());
  std::string x = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n";
  // The terrain: one quad surface per height frame, its points and fields the frame's own.
  if (!height_frames_.empty()) {
    const std::string points = std::to_string(static_cast<long long>(grid_.nx) * grid_.ny);
    x += "<Grid Name=\"terrain\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const Frame& f : height_frames_) {
      const std::string group = "/terrain/" + step_name(f.step);
      char time[64];
      std::snprintf(time, sizeof time, "%.17g", f.time);
      x += " <Grid Name=\"terrain_" + step_name(f.step) + "\" GridType=\"Uniform\">\n";
      x += "  <Time Value=\"" + std::string(time) + "\"/>\n";
      x += "  <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"" + quads + "\">" +
           hdf_item(quads + " 4", "Int", 4, "/grid/quads") + "</Topology>\n";
      x += "  <Geometry GeometryType=\"XYZ\">" +
           hdf_item(points + " 3", "Float", 8, group + "/points") + "</Geometry>\n";
      std::vector<std::string> scalars = {"height", "dh"};
      if (has_water_depth_) scalars.push_back("depth");
      if (has_speed_) scalars.push_back("speed");
      for (const std::string& name : scalars)
        x += "  <Attribute Name=\"" + name + "\" AttributeType=\"Scalar\" Center=\"Node\">" +
             hdf_item(grid, "Float", 4, group + "/" + name) + "</Attribute>\n";
      if (has_velocity_)
        x += "  <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">" +
             hdf_item(points + " 3", "Float", 4, group + "/velocity") + "</Attribute>\n";
      x += " </Grid>\n";
    }
    x += "</Grid>\n";
  }
  // The particles: a point cloud per snapshot.
  if (!particle_frames_.empty()) {
    x += "<Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const Frame& f : particle_frames_) {
      if (f.count == 0) continue;  // an empty point set upsets readers; the frame is in series.h5
      const std::string n = std::to_string(f.count), group = "/particles/" + step_name(f.step);
      char time[64];
      std::snprintf(time, sizeof time, "%.17g", f.time);
      x += " <Grid Name=\"particles_" + step_name(f.step) + "\" GridType=\"Uniform\">\n";
      x += "  <Time Value=\"" + std::string(time) + "\"/>\n";
      x += "  <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\">" + hdf_item(n, "UInt", 4, group + "/vertices") +
           "</Topology>\n";
      x += "  <Geometry GeometryType=\"XYZ\">" +
           hdf_item(n + " 3", "Float", 8, group + "/position") + "</Geometry>\n";
      x += "  <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">" +
           hdf_item(n + " 3", "Float", 4, group + "/velocity") + "</Attribute>\n";
      for (auto [name, type] : {std::pair{"density", "Float"}, std::pair{"age", "Float"},
                                std::pair{"sediment", "Int"}, std::pair{"id", "UInt"}}) {
        x += "  <Attribute Name=\"" + std::string(name) +
             "\" AttributeType=\"Scalar\" Center=\"Node\">" +
             hdf_item(n, type, 4, group + "/" + name) + "</Attribute>\n";
      }
      x += " </Grid>\n";
    }
    x += "</Grid>\n";
  }
  x += "</Domain>\n</Xdmf>\n";
  write_text_atomically((out_ / "series.xmf").string(), x);
}

}  // namespace runnel
