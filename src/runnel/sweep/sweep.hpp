// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/parameters.hpp"
#include "runnel/models/parameter_table.hpp"

namespace runnel {

// A parameter sweep (docs/sweeps.md): a base scenario, the axes to vary, how they combine, and the
// metrics to collect. Read and validated completely before anything runs.
struct SweepAxis {
  std::string key;                  // a parameter key (docs/parameters.md)
  std::vector<std::string> values;  // as parameter text, in the file's order
};

struct SweepSpec {
  std::string path;                        // the sweep file
  Parameters base = default_parameters();  // the base scenario (or the defaults)
  std::vector<SweepAxis> axes;             // in key order
  bool zip = false;  // combine: "grid" (every combination) or "zip" (the i-th of each)
  std::vector<std::string> metrics;  // collected into results.csv
  long long max_members = 1000;      // more needs --force
  long long checkpoint_every = 0;    // members checkpoint every N steps and resume from the newest
};

struct SweepMember {
  std::size_t index = 0;
  std::vector<std::string> values;           // one per axis
  Parameters params = default_parameters();  // the member's resolved scenario
};

// The metrics a sweep can collect: the run's volumes and balance, the shared terrain metrics.
std::vector<std::string> sweep_metric_names();

// Parses and validates a sweep file: unknown keys, empty axes, zipped axes of unequal length,
// unknown metrics, members that do not build (a bad value, a missing terrain file) are input
// errors naming the file and the problem.
SweepSpec read_sweep(const std::string& path);
std::vector<SweepMember> expand_sweep(const SweepSpec& spec);

// The number of members, computed from the axes without expanding them (a grid of ten axes of a
// thousand values is 10^30 members): at most kMaxSweepMembers + 1, which stands for "more".
inline constexpr long long kMaxSweepMembers = 1000000;
long long sweep_member_count(const SweepSpec& spec);
// Identifies the expanded sweep (every member's resolved scenario, in order): a folder holds one.
std::string sweep_id(const std::vector<SweepMember>& members);
// Makes `out` this sweep's folder: created if missing, its sweep.id written. Another sweep's folder
// is refused, unless `extend` and every member already begun there keeps its parameters.
void claim_sweep_folder(const std::string& out, const std::vector<SweepMember>& members,
                        bool extend);

// The member folder DIR/members/NNNN and the states a member is in, read from its folder: done
// (its result row was written, atomically, after its outputs), failed (its message), or pending.
std::string member_dir(const std::string& out, std::size_t index);
enum class MemberState { kPending, kRunning, kDone, kFailed };
MemberState member_state(const std::string& out, std::size_t index, std::string* message = nullptr);

// Runs one member in this process (on the default OpenCL device): its scenario.toml, the run's
// outputs and finally result.csv (the row of results.csv). A failure is written as `failed` and
// rethrown.
void run_member(const SweepSpec& spec, const SweepMember& member, const std::string& out,
                bool quiet);

// DIR/manifest.csv (every member's axis values and state) and DIR/results.csv (the rows of the
// done members, in member order); `running` lists members being run now.
void write_sweep_tables(const SweepSpec& spec, const std::vector<SweepMember>& members,
                        const std::string& out, const std::vector<std::size_t>& running = {});

// A SLURM array script that runs the members of the sweep, one per task, resumable on requeue.
std::string slurm_script(const SweepSpec& spec, const std::vector<SweepMember>& members,
                         const std::string& out, const std::string& runnel_binary,
                         const std::string& time_limit);

}  // namespace runnel
