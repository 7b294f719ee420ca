#include "body/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

namespace body {

namespace {

std::string reason(int err) {
  if (err == ENOSPC) return "disk full (no space left on device)";
  if (err == EDQUOT) return "disk quota exceeded";
  return std::strerror(err);
}

}  // namespace

void write_all(int fd, const void* data, std::size_t size, const std::string& label) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileWriteError(label + ": write failed: " + reason(errno));
    }
    if (n == 0) throw FileWriteError(label + ": write failed: " + reason(ENOSPC));
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void write_file_atomically(const std::filesystem::path& path, const void* data, std::size_t size) {
  const std::string target = path.string();
  if (path.filename().empty()) throw FileWriteError(target + ": not a file name");
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw FileWriteError(target + ": cannot write: the folder " + dir.string() + " does not exist");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw FileWriteError(target + ": cannot write: a folder has that name");
  }
  std::string tmpl = (dir / ("." + path.filename().string() + ".tmp-XXXXXX")).string();
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    throw FileWriteError(target + ": cannot create a temporary file in " + dir.string() + ": " +
                         reason(errno));
  }
  const std::string tmp(name.data());
  bool is_open = true;
  try {
    write_all(fd, data, size, target);
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
      throw FileWriteError(target + ": flushing to disk failed: " + reason(errno));
    }
    // mkstemp creates 0600; give the file the usual permissions (umask applies).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    if (::fchmod(fd, 0666 & ~mask) != 0) {
      throw FileWriteError(target + ": cannot set permissions: " + reason(errno));
    }
    is_open = false;
    if (::close(fd) != 0) throw FileWriteError(target + ": closing failed: " + reason(errno));
  } catch (...) {
    if (is_open) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw FileWriteError(target + ": cannot replace the file: " + reason(err));
  }
}

}  // namespace body
