// SPDX-License-Identifier: MIT
#include "runnel/compute/stderr_capture.hpp"

#include <unistd.h>

namespace runnel {

StderrCapture::StderrCapture() {
  std::fflush(stderr);
  file_ = std::tmpfile();
  if (!file_) return;
  saved_ = dup(STDERR_FILENO);
  if (saved_ < 0 || dup2(fileno(file_), STDERR_FILENO) < 0) {
    if (saved_ >= 0) close(saved_);
    saved_ = -1;
    std::fclose(file_);
    file_ = nullptr;
  }
}

StderrCapture::~StderrCapture() {
  release();
}

std::string StderrCapture::release() {
  if (!file_) return {};
  std::fflush(stderr);
  dup2(saved_, STDERR_FILENO);
  close(saved_);
  saved_ = -1;
  std::string text;
  std::rewind(file_);
  char chunk[4096];
  for (std::size_t got; (got = std::fread(chunk, 1, sizeof chunk, file_)) > 0;)
    text.append(chunk, got);
  std::fclose(file_);
  file_ = nullptr;
  return text;
}

}  // namespace runnel
