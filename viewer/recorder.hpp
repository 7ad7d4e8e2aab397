// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <string>

#include "runnel/io/images.hpp"

namespace runnel::viewer {

// The pixels of the bound framebuffer (w × h), top row first.
RgbImage read_framebuffer(int width, int height);

// An offscreen framebuffer of its own size (colour + depth), for screenshots at N× the window.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);  // throws when the GL cannot make one that large
  ~OffscreenTarget();
  void bind() const;
  static void unbind();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void release();
  unsigned fbo_ = 0, colour_ = 0, depth_ = 0;
  int width_, height_;
};

// Frames of one size to a video: an .mp4 through ffmpeg (H.264) when ffmpeg is on the PATH,
// otherwise (or for any other name) a PNG sequence frame_000000.png … in the folder `path`
// (for x.mp4 without ffmpeg: the folder x/).
class FrameRecorder {
 public:
  FrameRecorder(const std::string& path, double frames_per_second);
  ~FrameRecorder();
  void add(const RgbImage& frame);
  long long frames() const { return frames_; }
  // Where the frames go, for a message.
  const std::string& target() const { return target_; }

 private:
  std::string path_, target_;
  double fps_;
  bool video_ = false;
  std::FILE* pipe_ = nullptr;
  int width_ = 0, height_ = 0;
  long long frames_ = 0;
};

}  // namespace runnel::viewer
