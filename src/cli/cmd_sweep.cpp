// SPDX-License-Identifier: MIT
// runnel sweep: an ensemble of runs over parameters, seeds, models and terrains (docs/sweeps.md),
// run here by worker processes, or one member at a time by a SLURM array task.
#if RUNNEL_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only: the deprecated C++ bindings need their own library
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/sim/output_folder.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/sweep/sweep.hpp"

extern char** environ;

namespace runnel::cli {

namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string file, out = "runnel-sweep", time_limit = "24:00:00";
  int jobs = 0;
  long long member = -1;
  bool extend = false, force = false, slurm = false, quiet = false, collect = false;
};

int run_workers(const SweepOptions& opt, const SweepSpec& spec,
                const std::vector<SweepMember>& members) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::size_t> queue;
  std::size_t busy = 0;
  for (const SweepMember& m : members) {
    if (member_state(opt.out, m.index) == MemberState::kDone) continue;
    // A member another process is running now (a SLURM task, a --member run) is left to it.
    if (run_lock_held(member_dir(opt.out, m.index))) {
      ++busy;
      if (!opt.quiet)
        std::cerr << "sweep: member " << m.index << " is being run by another process; skipped\n";
      continue;
    }
    queue.push_back(m.index);
  }
  if (!opt.quiet) {
    std::cerr << "sweep: " << members.size() << " members, " << members.size() - queue.size() - busy
              << " done already, " << opt.jobs << " worker process" << (opt.jobs == 1 ? "" : "es")
              << "\n";
  }
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  int failed = 0;
  auto running_list = [&] {
    std::vector<std::size_t> list;
    for (auto& [pid, index] : running) list.push_back(index);
    return list;
  };
  while (next < queue.size() || !running.empty()) {
    while (next < queue.size() && static_cast<int>(running.size()) < opt.jobs) {
      const std::size_t index = queue[next++];
      std::vector<std::string> args = {
          self, "sweep", spec.path, "--out", opt.out, "--member", std::to_string(index), "--quiet"};
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      pid_t pid = 0;
      if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
        throw runtime_error("sweep: cannot start a worker process");
      running[pid] = index;
    }
    write_sweep_tables(spec, members, opt.out, running_list());
    int status = 0;
    const pid_t done = waitpid(-1, &status, 0);
    if (done < 0) throw runtime_error("sweep: lost track of the worker processes");
    const std::size_t index = running[done];
    running.erase(done);
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    failed += ok ? 0 : 1;
    if (!opt.quiet) std::cerr << "sweep: member " << index << (ok ? " done" : " failed") << "\n";
  }
  write_sweep_tables(spec, members, opt.out);
  return failed;
}

// Under mpirun (Open MPI's or a PMI launcher's environment), when runnel was built with MPI.
bool launched_by_mpi() {
#if RUNNEL_HAVE_MPI
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE");
#else
  return false;
#endif
}

// mpirun -np K runnel sweep: rank r runs members r, r + K, r + 2K, ... that are not done yet, each
// in this process (a deterministic stride: the same member always lands on the same rank); rank 0
// claims the folder first and writes the tables last. Returns the number of failed members.
int run_mpi(const SweepOptions& opt, const SweepSpec& spec,
            const std::vector<SweepMember>& members) {
#if RUNNEL_HAVE_MPI
  MPI_Init(nullptr, nullptr);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int claim_failed = 0;
  std::string claim_message;
  std::optional<FolderLock> lock;  // rank 0 coordinates: one sweep a folder at a time
  if (rank == 0) {
    try {
      claim_sweep_folder(opt.out, members, opt.extend);
      lock.emplace(opt.out, ".runnel-sweep.lock", "--out " + opt.out,
                   "--out " + opt.out +
                       ": another runnel sweep is running in this folder; wait for it to end");
    } catch (const Error& e) {
      claim_failed = 1;
      claim_message = e.what();
    }
  }
  MPI_Bcast(&claim_failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (claim_failed) {
    MPI_Finalize();
    if (rank == 0) throw input_error(claim_message);
    std::exit(2);
  }
  if (rank == 0 && !opt.quiet)
    std::cerr << "sweep: " << members.size() << " members on " << size << " MPI ranks\n";
  int failed = 0;
  for (std::size_t m = static_cast<std::size_t>(rank); m < members.size();
       m += static_cast<std::size_t>(size)) {
    if (member_state(opt.out, m) == MemberState::kDone) continue;
    try {
      run_member(spec, members[m], opt.out, true);
      if (!opt.quiet) std::cerr << "sweep: member " << m << " done on rank " << rank << "\n";
    } catch (const Error& e) {
      ++failed;
      std::cerr << "sweep: member " << m << " failed on rank " << rank << ": " << e.what() << "\n";
    }
  }
  int total = 0;
  MPI_Reduce(&failed, &total, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank == 0) write_sweep_tables(spec, members, opt.out);
  MPI_Finalize();
  if (rank != 0) std::exit(total > 0 ? 1 : 0);
  return total;
#else
  (void)opt, (void)spec, (void)members;
  return 0;
#endif
}

// Expands the sweep (counted first), then runs it, one member, its SLURM script, or its tables.
// Where the sweep's charts come from: the Python package draws them from results.csv.
std::string figures_hint(const std::string& out) {
  return " (figures: python3 -m runnel plot " + terminal_safe(out) + ")";
}

void sweep(SweepOptions opt) {
  const SweepSpec spec = read_sweep(opt.file);
  // Counted before anything is expanded: a sweep of 10^5 members is refused at once.
  const long long count = sweep_member_count(spec);
  if (count > spec.max_members && !opt.force) {
    throw input_error(opt.file + ": " +
                      (count > kMaxSweepMembers ? "more than " + std::to_string(kMaxSweepMembers)
                                                : std::to_string(count)) +
                      " members, more than max_members = " + std::to_string(spec.max_members) +
                      " (--force to run them anyway)");
  }
  const std::vector<SweepMember> members = expand_sweep(spec);
  if (opt.member >= static_cast<long long>(members.size())) {
    throw input_error("--member " + std::to_string(opt.member) + ": the sweep has members 0 to " +
                      std::to_string(members.size() - 1));
  }
  if (launched_by_mpi() && opt.member < 0 && !opt.slurm && !opt.collect) {
    const int failed = run_mpi(opt, spec, members);
    std::cout << terminal_safe(opt.out) << "/results.csv: " << members.size() - failed << " of "
              << members.size() << " members done" << figures_hint(opt.out) << "\n";
    if (failed > 0) throw runtime_error("sweep: " + std::to_string(failed) + " members failed");
    return;
  }
  // The script is composed (and its names checked) before the folder is claimed.
  const std::string script_text =
      opt.slurm ? slurm_script(spec, members, opt.out, fs::read_symlink("/proc/self/exe").string(),
                               opt.time_limit)
                : std::string();
  claim_sweep_folder(opt.out, members, opt.extend);
  if (opt.slurm) {
    const fs::path script = fs::path(opt.out) / "sweep.slurm";
    write_text_atomically(script.string(), script_text);
    std::cout << terminal_safe(script.string()) << ": sbatch it to run the " << members.size()
              << " members\n";
    return;
  }
  if (opt.collect) {
    write_sweep_tables(spec, members, opt.out);
    return;
  }
  if (opt.member >= 0) {
    const SweepMember& m = members[static_cast<std::size_t>(opt.member)];
    if (member_state(opt.out, m.index) == MemberState::kDone) return;  // a requeued task
    run_member(spec, m, opt.out, opt.quiet);
    return;
  }
  if (opt.jobs == 0) opt.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // One coordinating sweep a folder at a time (its workers and --member tasks do not take it).
  const FolderLock lock(
      opt.out, ".runnel-sweep.lock", "--out " + opt.out,
      "--out " + opt.out + ": another runnel sweep is running in this folder; wait for it to end");
  const int failed = run_workers(opt, spec, members);
  std::cout << terminal_safe(opt.out) << "/results.csv: " << members.size() - failed << " of "
            << members.size() << " members done" << figures_hint(opt.out) << "\n";
  if (failed > 0) {
    throw runtime_error("sweep: " + std::to_string(failed) + " members failed (messages in " +
                        opt.out + "/manifest.csv); run the command again to retry them");
  }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto opt = std::make_shared<SweepOptions>();
  auto* cmd = app.add_subcommand(
      "sweep",
      "Run an ensemble: every combination (or zip) of the parameter values in SWEEP.toml, each a "
      "normal run in DIR/members/NNNN, listed in DIR/manifest.csv with the metrics of the done "
      "ones "
      "in DIR/results.csv. Re-running skips done members and redoes interrupted ones; "
      "--member N runs one (a SLURM array task); `python -m runnel plot DIR` draws each metric "
      "against each varied parameter; see docs/sweeps.md");
  cmd->add_option("sweep", opt->file, "sweep file (TOML: [sweep] base, combine, metrics; [axes])")
      ->required();
  cmd->add_option("--out", opt->out, "the sweep's folder (created)")->capture_default_str();
  cmd->add_option("-j,--jobs", opt->jobs, "worker processes (default: one per core)")
      ->check(whole_in(1, 4096));
  cmd->add_option("--member", opt->member, "run only this member (0-based): one SLURM array task")
      ->check(whole_in(0, 100000000));
  cmd->add_flag("--extend", opt->extend,
                "accept a changed sweep file that keeps every begun member");
  cmd->add_flag("--force", opt->force, "run more members than the sweep's max_members");
  cmd->add_flag("--slurm-script", opt->slurm,
                "write DIR/sweep.slurm, an sbatch array script with one task per member, and exit");
  cmd->add_option("--time", opt->time_limit, "--slurm-script: each task's time limit")
      ->capture_default_str();
  cmd->add_flag("--collect", opt->collect,
                "only rewrite manifest.csv and results.csv from the members");
  cmd->add_flag("--quiet", opt->quiet, "no progress output");
  cmd->callback([opt] { sweep(*opt); });
}

}  // namespace runnel::cli
