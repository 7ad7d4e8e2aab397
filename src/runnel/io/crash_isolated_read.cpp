// SPDX-License-Identifier: MIT
#include "runnel/io/crash_isolated_read.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

#include "runnel/core/error.hpp"

namespace runnel {

void refuse_if_reading_crashes(const std::string& path, const std::function<void()>& read) {
  const pid_t child = fork();
  if (child < 0) return;  // no process to spare: the caller's read and its checks still run
  if (child == 0) {
    // _exit, not exit: no stdio buffer, open file or atexit handler of the parent's runs twice.
    try {
      read();
    } catch (...) {
    }
    _exit(0);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) return;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw input_error(path + ": damaged file (the library reading it crashed on its contents)");
  }
}

}  // namespace runnel
