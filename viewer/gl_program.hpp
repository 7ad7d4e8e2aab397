// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <string>

namespace runnel::viewer {

// A linked GLSL 3.30 program; compile and link errors throw with the driver's log.
class GlProgram {
 public:
  GlProgram(const char* vertex_source, const char* fragment_source);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  void use() const { glUseProgram(id_); }
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

}  // namespace runnel::viewer
