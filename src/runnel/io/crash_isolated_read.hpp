// SPDX-License-Identifier: MIT
#pragma once
#include <functional>
#include <string>

namespace runnel {

// Runs `read` (a reader of the file at `path`) once in a child process first. If the child dies
// instead of finishing (a signal, or a sanitizer's abnormal exit), the file is refused with one
// line, exit code 2, and the caller never reads it itself; an exception the reader throws in the
// child is left for the caller's own read to throw again. For libraries that crash on damaged files
// instead of reporting them (libhdf5 1.10.8: a chunk dimension of 0 divides by zero in H5Dopen2).
void refuse_if_reading_crashes(const std::string& path, const std::function<void()>& read);

}  // namespace runnel
