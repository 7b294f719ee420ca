#include "util/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <vector>

namespace util {

namespace {

// Linux file systems allow 255 bytes per name component.
constexpr std::size_t kNameMax = NAME_MAX;
constexpr const char* kSuffix = ".tmp-XXXXXX";  // mkstemp fills in the X

void sync_folder(const std::filesystem::path& dir) {
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return;  // the rename is done; a folder we cannot open cannot be flushed
  ::fsync(dfd);
  ::close(dfd);
}

}  // namespace

std::string describe_errno(int err) {
  if (err == ENOSPC) return "disk full (no space left on device)";
  if (err == EDQUOT) return "disk quota exceeded";
  if (err == EFBIG) return "file too large for this file system or limit";
  return std::strerror(err);
}

void write_all(int fd, const void* data, std::size_t size, const std::string& label) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileWriteError(label + ": write failed: " + describe_errno(errno));
    }
    if (n == 0) throw FileWriteError(label + ": write failed: " + describe_errno(ENOSPC));
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

std::filesystem::path temporary_name_for(const std::filesystem::path& path) {
  std::string base = path.filename().string();
  const std::size_t room = kNameMax - 1 - std::strlen(kSuffix);  // 1 for the leading dot
  if (base.size() > room) base.resize(room);  // bytes, not characters: only we see this name
  std::filesystem::path dir = path.parent_path();
  return dir / ("." + base + kSuffix);
}

void write_file_atomically(const std::filesystem::path& path, const void* data, std::size_t size,
                           bool create_folders) {
  const std::string target = path.string();
  if (path.empty() || path.filename().empty() || path.filename() == "." ||
      path.filename() == "..") {
    throw FileWriteError("'" + target + "': not a file name");
  }
  if (path.filename().string().size() > kNameMax) {
    throw FileWriteError(target + ": the file name is longer than " + std::to_string(kNameMax) +
                         " bytes");
  }
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (create_folders) {
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      throw FileWriteError(target + ": cannot create the folder " + dir.string() + ": " +
                           ec.message());
    }
  }
  if (!std::filesystem::is_directory(dir, ec)) {
    throw FileWriteError(target + ": cannot write: the folder " + dir.string() + " does not exist");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw FileWriteError(target + ": cannot write: that is a folder; give a file name");
  }
  // Renaming over a device or a pipe would replace it (as root, /dev/full itself) and write
  // nothing where the user looks: such a target is refused. A link is replaced, not followed.
  if (struct stat st{};
      ::lstat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode)) {
    throw FileWriteError(target +
                         ": cannot write: that is a device, pipe or socket, not a file; "
                         "give a file name");
  }
  const std::string tmpl = (dir / temporary_name_for(path).filename()).string();
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    throw FileWriteError(target + ": cannot create a temporary file in " + dir.string() + ": " +
                         describe_errno(errno));
  }
  const std::string tmp(name.data());
  bool is_open = true;
  try {
    write_all(fd, data, size, target);
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
      throw FileWriteError(target + ": flushing to disk failed: " + describe_errno(errno));
    }
    // mkstemp creates 0600; give the file the usual permissions (umask applies).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    if (::fchmod(fd, 0666 & ~mask) != 0) {
      throw FileWriteError(target + ": cannot set permissions: " + describe_errno(errno));
    }
    is_open = false;
    if (::close(fd) != 0) {
      throw FileWriteError(target + ": closing failed: " + describe_errno(errno));
    }
  } catch (...) {
    if (is_open) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw FileWriteError(target + ": cannot replace the file: " + describe_errno(err));
  }
  sync_folder(dir);
}

}  // namespace util
