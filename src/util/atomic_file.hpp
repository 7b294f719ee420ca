// The one way this tool writes a file. The bytes go to a temporary file in the target's
// folder, are flushed to disk, the temporary file is renamed over the target and the folder
// is flushed too: a failure (disk full, no permission, a crash) at any moment leaves the old
// file or the new one, never a torn or empty one.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace util {

class FileWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws FileWriteError naming the file and the reason ("disk full", "permission denied",
// "is a folder", "a device, pipe or socket"). Does not create missing folders unless
// `create_folders` is set.
void write_file_atomically(const std::filesystem::path& path, const void* data, std::size_t size,
                           bool create_folders = false);
inline void write_file_atomically(const std::filesystem::path& path, const std::string& bytes,
                                  bool create_folders = false) {
  write_file_atomically(path, bytes.data(), bytes.size(), create_folders);
}

// Writes all bytes to an open descriptor (retrying short writes and EINTR); throws
// FileWriteError "<label>: <reason>" (ENOSPC reads "disk full"). Exposed for tests.
void write_all(int fd, const void* data, std::size_t size, const std::string& label);

// The temporary name used for `path`: in the same folder, hidden, and never longer than the
// file system's name limit even when the target's own name is at that limit.
std::filesystem::path temporary_name_for(const std::filesystem::path& path);

// Text for an errno value a user can act on ("disk full (no space left on device)").
std::string describe_errno(int err);

}  // namespace util
