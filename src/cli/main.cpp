// SPDX-License-Identifier: MIT
// runnel: the command line. Exit codes: 0 ok, 1 runtime failure, 2 usage or input error.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/core/version.hpp"

namespace {

// The message on one line, bounded: whatever text of a file or a flag it echoes, a line of at most
// kMostMessageBytes (a megabyte-long name in a scenario gives a line, not a megabyte).
constexpr std::size_t kMostMessageBytes = 2000;
int fail(const std::string& message, runnel::ExitCode code) {
  std::string line = runnel::terminal_safe(message);
  if (line.size() > kMostMessageBytes)
    line = line.substr(0, kMostMessageBytes) + "... (" +
           std::to_string(line.size() - kMostMessageBytes) + " more bytes)";
  std::cerr << "runnel: " << line << "\n";
  return static_cast<int>(code);
}

// What was printed must have reached its destination: `runnel params > /dev/full` is a failure.
int finish_output(int code) {
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    const int e = errno;
    std::cerr << "runnel: cannot write the standard output (" << std::strerror(e) << ")\n";
    return code == 0 ? static_cast<int>(runnel::ExitCode::kRuntime) : code;
  }
  return code;
}

int run(int argc, char** argv) {
  CLI::App app{
      "runnel: SPH particle hydraulic erosion of terrain heightmaps, with comparison models.\n"
      "Every subcommand has --help. Exit codes: 0 ok, 1 runtime failure, 2 usage or input error."};
  app.set_version_flag("--version",
                       std::string("runnel ") + runnel::kVersion + " (" + runnel::kRevision + ")");
  app.require_subcommand(1);
  runnel::cli::add_run_command(app);
  runnel::cli::add_resume_command(app);
  runnel::cli::add_compare_command(app);
  runnel::cli::add_sweep_command(app);
  runnel::cli::add_export_command(app);
  runnel::cli::add_devices_command(app);
  runnel::cli::add_generate_command(app);
  runnel::cli::add_convert_command(app);
  runnel::cli::add_info_command(app);
  runnel::cli::add_params_command(app);
  runnel::cli::add_validate_command(app);
  runnel::cli::add_bench_command(app);
  runnel::cli::refuse_unclear_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(std::string(e.what()) + " (see 'runnel --help')", runnel::ExitCode::kUsage);
  } catch (const runnel::Error& e) {
    return fail(e.what(), e.code());
  } catch (const cl::Error& e) {
    return fail(std::string("OpenCL error in ") + e.what() + ": " + runnel::cl_error_name(e.err()) +
                    " (" + std::to_string(e.err()) + ")",
                runnel::ExitCode::kRuntime);
  } catch (const std::bad_alloc&) {
    return fail("out of memory", runnel::ExitCode::kRuntime);
  } catch (const std::exception& e) {
    return fail(e.what(), runnel::ExitCode::kRuntime);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe or a file-size limit must be a write error runnel reports (exit 1), not a
  // signal that kills it half-way through an output.
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  return finish_output(run(argc, argv));
}
