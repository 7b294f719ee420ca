// Atomic file writes: the bytes go to a temporary file next to the target, are flushed to
// disk, and only then renamed over the target. A failure leaves the old file untouched.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace body {

class FileWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws FileWriteError naming the file and the reason ("disk full", "permission denied").
void write_file_atomically(const std::filesystem::path& path, const void* data, std::size_t size);
inline void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
  write_file_atomically(path, bytes.data(), bytes.size());
}

// Writes all bytes to an open descriptor (retrying short writes and EINTR); throws
// FileWriteError "<label>: <reason>" (ENOSPC reads "disk full"). Exposed for tests.
void write_all(int fd, const void* data, std::size_t size, const std::string& label);

}  // namespace body
