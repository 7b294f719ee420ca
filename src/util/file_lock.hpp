// An advisory lock that says "this file is in use by a running program": flock() on a lock
// file beside it. The kernel drops the lock when the process ends however it ends (kill -9,
// a crash), so a stale lock file never blocks anyone; only a live holder does.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace util {

class FileLock {
 public:
  enum class Outcome { kAcquired, kHeldElsewhere, kUnavailable };

  // Tries to lock `lock_path` (created if missing, with its folder) without waiting.
  // kHeldElsewhere: another process holds it. kUnavailable: the lock file cannot be created
  // or locked (read-only folder, a file system without locks); `problem` says why.
  static Outcome try_acquire(const std::filesystem::path& lock_path, std::optional<FileLock>& lock,
                             std::string* problem = nullptr);

  FileLock(FileLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  explicit FileLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// "<file>.lock": where the lock for `path` lives.
std::filesystem::path lock_path_for(const std::filesystem::path& path);

}  // namespace util
