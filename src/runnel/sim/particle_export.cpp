// SPDX-License-Identifier: MIT
#include "runnel/sim/particle_export.hpp"

#include <bit>
#include <cstdio>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/vtk_xml.hpp"

namespace runnel {

namespace {

void require_particles(const std::string& path, const CheckpointData& d) {
  if (d.model != "sph")
    throw input_error(path + ": the " + d.model + " model has no particles to export");
}

}  // namespace

MapParticles map_particles(const HostParticles& p, const Heightmap& terrain) {
  const MapFrame map(terrain);
  const std::size_t n = p.size();
  MapParticles m{std::vector<double>(3 * n), std::vector<float>(3 * n), p.id};
  for (std::size_t k = 0; k < n; ++k) {
    m.position[3 * k] = map.x(p.f[kX][k]);
    m.position[3 * k + 1] = map.y(p.f[kZ][k]);
    m.position[3 * k + 2] = p.f[kY][k];
    m.velocity[3 * k] = p.f[kVx][k];
    m.velocity[3 * k + 1] = -p.f[kVz][k];
    m.velocity[3 * k + 2] = p.f[kVy][k];
    m.id[k] &= ~kDeadFlag;
  }
  return m;
}

void write_particles_ply(const std::string& path, const CheckpointData& d) {
  static_assert(std::endian::native == std::endian::little,
                "the PLY body is written as it lies in memory");
  require_particles(path, d);
  const HostParticles& p = d.particles;
  const MapParticles m = map_particles(p, d.terrain);
  write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(
        f,
        "ply\nformat binary_little_endian 1.0\ncomment runnel SPH particles, step %llu, t = %.9g "
        "s, "
        "map frame (x east, y north, z up)\nelement vertex %zu\nproperty double x\nproperty double "
        "y\nproperty double z\nproperty float vx\nproperty float vy\nproperty float vz\nproperty "
        "float density\nproperty int sediment\nproperty float age\nproperty uint id\nend_header\n",
        static_cast<unsigned long long>(d.steps), d.time, p.size());
    for (std::size_t k = 0; k < p.size(); ++k) {
      const float density = p.f[kRho][k], age = p.f[kAge][k];
      const std::int32_t sediment = p.sediment[k];
      std::fwrite(&m.position[3 * k], sizeof(double), 3, f);
      std::fwrite(&m.velocity[3 * k], sizeof(float), 3, f);
      std::fwrite(&density, sizeof density, 1, f);
      std::fwrite(&sediment, sizeof sediment, 1, f);
      std::fwrite(&age, sizeof age, 1, f);
      std::fwrite(&m.id[k], sizeof(std::uint32_t), 1, f);
    }
    if (std::ferror(f)) throw runtime_error(path + ": write failed");
  });
}

void write_particles_vtp(const std::string& path, const HostParticles& p, const MapParticles& m) {
  const std::size_t n = p.size();
  std::vector<std::int64_t> connectivity(n), offsets(n);
  for (std::size_t k = 0; k < n; ++k) {
    connectivity[k] = static_cast<std::int64_t>(k);
    offsets[k] = static_cast<std::int64_t>(k + 1);
  }
  const std::vector<VtkSection> sections = {
      {"PointData",
       "Scalars=\"density\" Vectors=\"velocity\"",
       {{"velocity", "Float32", 3, m.velocity.data(), m.velocity.size() * sizeof(float)},
        {"density", "Float32", 1, p.f[kRho].data(), n * sizeof(float)},
        {"sediment", "Int32", 1, p.sediment.data(), n * sizeof(std::int32_t)},
        {"age", "Float32", 1, p.f[kAge].data(), n * sizeof(float)},
        {"id", "UInt32", 1, m.id.data(), n * sizeof(std::uint32_t)}}},
      {"Points",
       "",
       {{"Points", "Float64", 3, m.position.data(), m.position.size() * sizeof(double)}}},
      {"Verts",
       "",
       {{"connectivity", "Int64", 1, connectivity.data(), n * 8},
        {"offsets", "Int64", 1, offsets.data(), n * 8}}}};
  write_vtk_xml(path, "PolyData", "",
                "NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" +
                    std::to_string(n) +
                    "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\"",
                sections);
}

void write_particles_vtp(const std::string& path, const CheckpointData& d) {
  require_particles(path, d);
  write_particles_vtp(path, d.particles, map_particles(d.particles, d.terrain));
}

}  // namespace runnel
