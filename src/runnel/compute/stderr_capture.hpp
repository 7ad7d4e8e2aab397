// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <string>

namespace runnel {

// Takes what is written to the process's standard error (file descriptor 2) while it lives, so
// that it can be kept instead of shown. PoCL compiles with clang in the process, and clang prints
// its "N warnings generated." straight to descriptor 2, outside the build log that OpenCL returns:
// a successful kernel build must not leave compiler output on a user's terminal. Where the capture
// cannot be set up (no temporary file), nothing is taken and text() is empty.
class StderrCapture {
 public:
  StderrCapture();
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  // Restores descriptor 2 and returns what was written to it meanwhile (once; empty afterwards).
  std::string release();

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

}  // namespace runnel
