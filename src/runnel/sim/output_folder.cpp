// SPDX-License-Identifier: MIT
#include "runnel/sim/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"

namespace runnel {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLockName = ".runnel.lock";
constexpr const char* kRunMarker = ".runnel-run";

std::string read_marker(const fs::path& file) {
  std::ifstream in(file);
  std::string id;
  std::getline(in, id);
  return id;
}

// The earlier run's files present in the folder: runnel's own output names and checkpoints only;
// nothing else in the folder is ever touched, and nothing through a link (a link named like an
// output is itself the entry; a linked checkpoints/ folder is refused by the caller).
std::vector<fs::path> earlier_outputs(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const std::string& name : run_output_names())
    if (fs::exists(fs::symlink_status(dir / name, ec))) found.push_back(dir / name);
  // The series' VTK frames (series_vtk/terrain_*.vts, particles_*.vtp), unless the folder is a
  // link.
  if (!fs::is_symlink(dir / "series_vtk", ec))
    for (const auto& e : fs::directory_iterator(dir / "series_vtk", ec)) {
      const std::string f = e.path().filename().string(), x = e.path().extension().string();
      if ((f.rfind("terrain_", 0) == 0 && x == ".vts") ||
          (f.rfind("particles_", 0) == 0 && x == ".vtp"))
        found.push_back(e.path());
    }
  if (fs::is_symlink(dir / "checkpoints", ec)) return found;
  for (const auto& e : fs::directory_iterator(dir / "checkpoints", ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("step_", 0) == 0 && e.path().extension() == ".h5") found.push_back(e.path());
  }
  return found;
}

}  // namespace

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names = {
      "final.h5",          "height_initial.png", "height_final.png",  "erosion.png",
      "final.asc",         "final.npy",          "final.tif",         "erosion.tif",
      "drainage_area.npy", "metrics.json",       "probes.csv",        "outflow.csv",
      "series.h5",         "series.h5.partial",  "series.xmf",        "series.pvd",
      "geology.png",       "exposed_layer.tif",  "exposed_layer.npy", "sediment_thickness.tif"};
  return names;
}

bool run_lock_held(const std::string& dir) {
  const int fd = ::open((fs::path(dir) / kLockName).c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
  ::close(fd);
  return held;
}

FolderLock::FolderLock(const std::string& dir, const std::string& name, const std::string& who,
                       const std::string& busy) {
  const std::string path = (fs::path(dir) / name).string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw input_error(who + ": cannot write into the output folder (" + std::strerror(errno) + ")");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw input_error(busy);
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

OutputFolder::OutputFolder(const std::string& dir_text, const std::string& run_id, bool overwrite) {
  const fs::path dir(dir_text);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw input_error("--out " + dir_text + ": cannot create the output folder");

  lock_.emplace(dir_text, kLockName, "--out " + dir_text,
                "--out " + dir_text +
                    ": another runnel run is writing into this folder; wait for it to end or "
                    "choose another --out");
  // Rolling checkpoints are written into checkpoints/ and old ones removed: never through a
  // link into another folder.
  if (fs::is_symlink(dir / "checkpoints", ec))
    throw input_error("--out " + dir_text +
                      ": checkpoints is a link; runnel neither writes nor removes through it "
                      "(choose another --out)");
  const std::string earlier = read_marker(dir / kRunMarker);
  const std::vector<fs::path> outputs = earlier_outputs(dir);
  if (earlier != run_id && !outputs.empty()) {
    // Only what a run recorded here wrote is replaced: in a folder runnel never wrote into (no
    // marker), a file of an output's name is the user's own.
    if (earlier.empty())
      throw input_error("--out " + dir_text + ": holds " + outputs.front().filename().string() +
                        ", which no runnel run wrote there; choose another --out");
    if (!overwrite)
      throw input_error("--out " + dir_text + ": holds the outputs of another run (" +
                        outputs.front().filename().string() +
                        "); choose another --out, or --overwrite to replace them");
    for (const fs::path& p : outputs) fs::remove(p, ec);
  }
  // Written as every output is (a temporary, then a rename): a folder that let the lock be
  // opened but takes no new file (a read-only mount that had the lock) is refused here, before
  // the first step.
  write_text_atomically((dir / kRunMarker).string(), run_id + "\n");
}

}  // namespace runnel
