// SPDX-License-Identifier: MIT
#include "runnel/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "runnel/core/error.hpp"

namespace runnel {

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& write) {
  write_path_atomically(path, [&](const std::string& temporary) {
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (!f) throw runtime_error(path + ": cannot open a temporary file: " + std::strerror(errno));
    try {
      write(f);
      if (std::fflush(f) != 0)
        throw runtime_error(path + ": write failed: " + std::strerror(errno));
    } catch (...) {
      std::fclose(f);
      throw;
    }
    if (std::fclose(f) != 0) throw runtime_error(path + ": write failed: " + std::strerror(errno));
  });
}

void write_path_atomically(const std::string& path,
                           const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw input_error(path + ": output directory '" + dir.string() + "' does not exist");
  }
  std::string hidden_name(".");
  hidden_name.append(target.filename().string()).append(".tmpXXXXXX");
  std::string tmp_name = (dir / hidden_name).string();
  const int fd = mkstemp(tmp_name.data());
  if (fd < 0)
    throw runtime_error(path + ": cannot create a temporary file: " + std::strerror(errno));
  close(fd);
  try {
    write(tmp_name);
    const int sync_fd = open(tmp_name.c_str(), O_RDONLY);
    if (sync_fd < 0 || fsync(sync_fd) != 0) {
      if (sync_fd >= 0) close(sync_fd);
      throw runtime_error(path + ": sync failed: " + std::strerror(errno));
    }
    close(sync_fd);
  } catch (...) {
    unlink(tmp_name.c_str());
    throw;
  }
  fs::permissions(tmp_name,
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                      fs::perms::others_read,
                  ec);
  if (std::rename(tmp_name.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    unlink(tmp_name.c_str());
    throw runtime_error(path + ": cannot rename the temporary file into place: " + reason);
  }
}

}  // namespace runnel
