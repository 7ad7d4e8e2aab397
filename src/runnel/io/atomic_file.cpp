// SPDX-License-Identifier: MIT
#include "runnel/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "runnel/core/error.hpp"
#include "runnel/io/output_paths.hpp"

namespace runnel {
namespace {

// The exit-code rule (README): a path the user gave that cannot be written is bad input (2); a
// failure while writing (a full disk, an I/O error) is a runtime failure (1).
[[noreturn]] void throw_write_error(const std::string& message, int e) {
  if (e == EACCES || e == EPERM || e == EROFS || e == ENOTDIR || e == ENOENT || e == ENAMETOOLONG ||
      e == EISDIR)
    throw input_error(message);
  throw runtime_error(message);
}

}  // namespace

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

void write_text_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::FILE* f) {
    if (std::fwrite(text.data(), 1, text.size(), f) != text.size())
      throw runtime_error(path + ": write failed: " + std::strerror(errno));
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
  refuse_special_output(path);  // a rename would replace a device node or a FIFO
  std::string hidden_name(".");
  hidden_name.append(target.filename().string()).append(".tmpXXXXXX");
  std::string tmp_name = (dir / hidden_name).string();
  const int fd = mkstemp(tmp_name.data());
  if (fd < 0) {
    const int e = errno;
    throw_write_error(path + ": cannot write here: " + std::strerror(e), e);
  }
  close(fd);
  try {
    write(tmp_name);
    const int sync_fd = open(tmp_name.c_str(), O_RDONLY);
    if (sync_fd < 0 || fsync(sync_fd) != 0) {
      if (sync_fd >= 0) close(sync_fd);
      throw runtime_error(path + ": sync failed: " + std::strerror(errno));
    }
    close(sync_fd);
  } catch (const Error& e) {
    unlink(tmp_name.c_str());
    // Name the file the user asked for, not the hidden temporary.
    std::string message = e.what();
    for (auto at = message.find(tmp_name); at != std::string::npos; at = message.find(tmp_name))
      message.replace(at, tmp_name.size(), path);
    throw Error(e.code(), message);
  } catch (...) {
    unlink(tmp_name.c_str());
    throw;
  }
  fs::permissions(tmp_name,
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                      fs::perms::others_read,
                  ec);
  if (std::rename(tmp_name.c_str(), path.c_str()) != 0) {
    const int e = errno;
    unlink(tmp_name.c_str());
    throw_write_error(path + ": cannot put the file in place: " + std::strerror(e), e);
  }
  // The rename is durable only once the directory entry is on disk too.
  const int dir_fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (dir_fd >= 0) {
    const bool synced = fsync(dir_fd) == 0;
    close(dir_fd);
    if (!synced) throw runtime_error(path + ": sync of its folder failed: " + std::strerror(errno));
  }
}

int remove_stale_temporaries(const std::string& dir, const std::string& prefix) {
  namespace fs = std::filesystem;
  std::error_code ec;
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("." + prefix, 0) == 0 && name.find(".tmp") != std::string::npos &&
        entry.is_regular_file(ec) && fs::remove(entry.path(), ec)) {
      ++removed;
    }
  }
  return removed;
}

}  // namespace runnel
