#include "util/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace util {

FileLock::Outcome FileLock::try_acquire(const std::filesystem::path& lock_path,
                                        std::optional<FileLock>& lock, std::string* problem) {
  lock.reset();
  std::error_code ec;
  if (!lock_path.parent_path().empty())
    std::filesystem::create_directories(lock_path.parent_path(), ec);
  // O_NOFOLLOW: a link planted where the lock file goes is never followed (and never created
  // through).
  const int fd =
      ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NOCTTY, 0644);
  if (fd < 0) {
    if (problem != nullptr) {
      *problem = lock_path.string() + ": cannot create the lock file: " + std::strerror(errno);
    }
    return Outcome::kUnavailable;
  }
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    if (err == EINTR) continue;
    ::close(fd);
    if (err == EWOULDBLOCK) return Outcome::kHeldElsewhere;
    if (problem != nullptr) *problem = lock_path.string() + ": cannot lock: " + std::strerror(err);
    return Outcome::kUnavailable;
  }
  lock.emplace(FileLock(fd));
  return Outcome::kAcquired;
}

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

std::filesystem::path lock_path_for(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  p += ".lock";
  return p;
}

}  // namespace util
