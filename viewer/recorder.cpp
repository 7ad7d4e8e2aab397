// SPDX-License-Identifier: MIT
#include "recorder.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"

namespace runnel::viewer {

RgbImage read_framebuffer(int w, int h) {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y) {  // GL rows start at the bottom
    std::copy_n(pixels.data() + static_cast<std::size_t>(h - 1 - y) * w * 3,
                static_cast<std::size_t>(w) * 3,
                image.rgb.data() + static_cast<std::size_t>(y) * w * 3);
  }
  return image;
}

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
  GLint most = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &most);
  if (width > most || height > most) {
    throw input_error("screenshot of " + std::to_string(width) + "x" + std::to_string(height) +
                      ": this OpenGL allows at most " + std::to_string(most) + " pixels a side");
  }
  glGenFramebuffers(1, &fbo_);
  glGenRenderbuffers(1, &colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    release();
    throw runtime_error("cannot make an offscreen framebuffer of " + std::to_string(width) + "x" +
                        std::to_string(height));
  }
}

OffscreenTarget::~OffscreenTarget() {
  release();
}

void OffscreenTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (colour_) glDeleteRenderbuffers(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  fbo_ = colour_ = depth_ = 0;
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
}
void OffscreenTarget::unbind() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

namespace {
// 'text' for sh, with each ' written as '\''.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool have_ffmpeg() {
  return std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
}
}  // namespace

FrameRecorder::FrameRecorder(const std::string& path, double fps) : path_(path), fps_(fps) {
  const std::filesystem::path p(path);
  video_ = p.extension() == ".mp4" && have_ffmpeg();
  if (video_) {
    target_ = path;
  } else {
    target_ = p.extension() == ".mp4" ? (p.parent_path() / p.stem()).string() : path;
    std::error_code error;
    std::filesystem::create_directories(target_, error);
    if (error) throw input_error("--record " + target_ + ": " + error.message());
  }
}

FrameRecorder::~FrameRecorder() {
  if (pipe_ && pclose(pipe_) != 0)
    std::fprintf(stderr, "runnel-viewer: ffmpeg failed to write %s\n",
                 terminal_safe(path_).c_str());
}

void FrameRecorder::add(const RgbImage& frame) {
  if (!video_) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06lld.png", frames_);
    write_png_rgb((std::filesystem::path(target_) / name).string(), frame);
    ++frames_;
    return;
  }
  if (!pipe_) {
    width_ = frame.width;
    height_ = frame.height;
    // H.264 in yuv420p needs even sizes: pad by a pixel where odd.
    const std::string cmd = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " +
                            std::to_string(width_) + "x" + std::to_string(height_) + " -r " +
                            std::to_string(fps_) +
                            " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt "
                            "yuv420p -crf 18 " +
                            shell_quoted(path_);
    pipe_ = popen(cmd.c_str(), "w");
    if (!pipe_) throw runtime_error("--record " + path_ + ": cannot start ffmpeg");
  }
  if (frame.width != width_ || frame.height != height_) return;  // a resized window: skipped
  std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_);
  ++frames_;
}

}  // namespace runnel::viewer
