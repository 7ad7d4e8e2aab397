// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <cstddef>
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel::viewer {

// The pieces a mesh on the terrain's grid and its textures are made of.

// Two triangles per cell, split along the diagonal (i, j)–(i+1, j+1) as the simulation's mesh is,
// so whatever is drawn on the grid meets the terrain along the same edges.
std::vector<GLuint> grid_triangles(int nx, int ny);
// x, z and height of every vertex (row-major).
std::vector<float> grid_positions(const Heightmap& terrain);
// A new buffer bound to `target` with `bytes` of `data` (zeros when null).
GLuint make_buffer(GLenum target, std::size_t bytes, const void* data, GLenum usage);
// A new 2-D texture, bound, filtered bilinearly and clamped at its edges (no storage yet).
GLuint make_texture();
// Vertex attribute `location`: `components` floats a vertex from the bound array buffer.
void float_attribute(GLuint location, int components);

}  // namespace runnel::viewer
