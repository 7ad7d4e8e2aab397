// SPDX-License-Identifier: MIT
#pragma once
#include <stdexcept>
#include <string>

namespace runnel {

// Exit codes of every runnel program: the CLI maps an Error to its code.
enum class ExitCode : int { kOk = 0, kRuntime = 1, kUsage = 2 };

// The one exception type of the project. It carries the exit code the CLI returns, so code deep
// in a reader decides whether a failure is the user's input (2) or a runtime failure (1).
class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

// Bad input: a file, a scenario key or a flag. The message names the thing and the problem.
inline Error input_error(const std::string& message) {
  return Error(ExitCode::kUsage, message);
}
// A failure while running: a device error, a numerical blow-up.
inline Error runtime_error(const std::string& message) {
  return Error(ExitCode::kRuntime, message);
}

}  // namespace runnel
