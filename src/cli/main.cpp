// SPDX-License-Identifier: MIT
// runnel: the command line. Exit codes: 0 ok, 1 runtime failure, 2 usage or input error.
#include <iostream>

#include "cli/commands.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/version.hpp"

int main(int argc, char** argv) {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "runnel: " << e.what() << " (see 'runnel --help')\n";
    return static_cast<int>(runnel::ExitCode::kUsage);
  } catch (const runnel::Error& e) {
    std::cerr << "runnel: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const cl::Error& e) {
    std::cerr << "runnel: OpenCL error in " << e.what() << ": " << runnel::cl_error_name(e.err())
              << " (" << e.err() << ")\n";
    return static_cast<int>(runnel::ExitCode::kRuntime);
  } catch (const std::bad_alloc&) {
    std::cerr << "runnel: out of memory\n";
    return static_cast<int>(runnel::ExitCode::kRuntime);
  } catch (const std::exception& e) {
    std::cerr << "runnel: " << e.what() << "\n";
    return static_cast<int>(runnel::ExitCode::kRuntime);
  }
  return 0;
}
