// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace runnel {

// The names of every file a run writes into its --out folder (beside checkpoints/step_*.h5).
const std::vector<std::string>& run_output_names();

// The --out folder of one run, held for as long as the run writes into it:
// - locked (an flock on DIR/.runnel.lock): a second run into the same folder is refused while
//   this one lives, so two runs cannot leave a mix of their files;
// - proven writable before the first step (its lock and DIR/.runnel-run are created), so a
// read-only
//   folder is refused at once, not after the whole run;
// - holding only this run's outputs: DIR/.runnel-run names the run (its parameters and its
//   terrain's content); outputs of another run in the folder are refused, or removed with
//   `overwrite`. A resume of the same run, or the same run again, replaces its own files.
// Whether a live runnel run holds `dir`'s run lock now (a folder without one: false).
bool run_lock_held(const std::string& dir);

// An exclusive lock on `name` in `dir` (created), held while the object lives; refused with
// `busy` (an input error) when another process holds it, and with "`who`: cannot write into the
// output folder" when the lock file cannot be opened. Closing the descriptor (even a killed
// process's) releases it.
class FolderLock {
 public:
  FolderLock(const std::string& dir, const std::string& name, const std::string& who,
             const std::string& busy);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

class OutputFolder {
 public:
  OutputFolder(const std::string& dir, const std::string& run_id, bool overwrite);
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

 private:
  std::optional<FolderLock> lock_;
};

}  // namespace runnel
