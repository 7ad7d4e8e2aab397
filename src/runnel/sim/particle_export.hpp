// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/sph/particle_store.hpp"

namespace runnel {

// SPH particles in the map frame every export shares (docs/series.md): positions (x east, y
// north, z up; float64, map coordinates can be millions of metres) and velocities (float32) as n ×
// 3 rows, and the stable ids without the store's dead flag.
struct MapParticles {
  std::vector<double> position;
  std::vector<float> velocity;
  std::vector<std::uint32_t> id;
};
MapParticles map_particles(const HostParticles& particles, const Heightmap& terrain);

// A checkpoint's SPH particles as a binary PLY file (splashsurf, MeshLab, meshio): positions,
// velocity, density, sediment, age and the stable id per vertex.
void write_particles_ply(const std::string& path, const CheckpointData& data);

// The same as VTK's XML PolyData (.vtp, raw appended binary): each particle a vertex cell, every
// field a point array, so ParaView's default reader draws the particles and colours them by any
// field (its PLY reader reads the positions only: neither cells nor other properties).
void write_particles_vtp(const std::string& path, const CheckpointData& data);
// The same for particles in memory, already in the map frame (`mapped`: map_particles of them).
void write_particles_vtp(const std::string& path, const HostParticles& particles,
                         const MapParticles& mapped);

}  // namespace runnel
