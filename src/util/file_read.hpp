// The one way this tool reads a whole file it was given (sessions, ui.json, photos, survey
// tables). It opens only regular files: a pipe or a device would block the reader or never end,
// so the file is opened without blocking and checked on the open descriptor (no window between
// the check and the read). A size limit is checked before anything is allocated.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace util {

class FileReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The whole file. Throws FileReadError "<file>: <problem>": no such file, not a regular file
// (a folder, pipe, device or socket), larger than `max_bytes`, or unreadable (with the reason).
std::string read_regular_file(const std::filesystem::path& path, std::size_t max_bytes);

// "12.3 MB", "640 KB", "512 bytes": sizes in messages.
std::string describe_size(std::size_t bytes);

}  // namespace util
