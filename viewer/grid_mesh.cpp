// SPDX-License-Identifier: MIT
#include "grid_mesh.hpp"

namespace runnel::viewer {

std::vector<GLuint> grid_triangles(int nx, int ny) {
  std::vector<GLuint> index;
  index.reserve(static_cast<std::size_t>(nx - 1) * (ny - 1) * 6);
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const GLuint a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      index.insert(index.end(), {a, c, b, a, d, c});
    }
  }
  return index;
}

std::vector<float> grid_positions(const Heightmap& t) {
  std::vector<float> grid;
  grid.reserve(t.size() * 3);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      grid.push_back(static_cast<float>(i * t.cell));
      grid.push_back(static_cast<float>(j * t.cell));
      grid.push_back(t.at(i, j));
    }
  }
  return grid;
}

GLuint make_buffer(GLenum target, std::size_t bytes, const void* data, GLenum usage) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(target, buffer);
  const std::vector<unsigned char> zeros(data ? 0 : bytes, 0);
  glBufferData(target, static_cast<GLsizeiptr>(bytes), data ? data : zeros.data(), usage);
  return buffer;
}

GLuint make_texture() {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

void float_attribute(GLuint location, int components) {
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(location);
}

}  // namespace runnel::viewer
