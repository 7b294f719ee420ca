// Session files: where they live, atomic autosave, and loading that never loses a file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "app/session.hpp"

namespace app {

// $XDG_STATE_HOME/sequential-gallery/session.json, else ~/.local/state/sequential-gallery/...
std::filesystem::path default_session_path();

// Writes text to a temporary file beside `path`, fsyncs it, renames it over `path` and fsyncs
// the directory: a crash at any moment leaves the old or the new file, never a torn one.
// Throws std::runtime_error naming the file and the reason (e.g. disk full).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

void save_session(const Session& session, const std::filesystem::path& path);

struct LoadResult {
  std::optional<Session> session;   // set when the file existed and was valid
  std::string problem;              // non-empty when the file was unreadable or corrupt
  std::filesystem::path set_aside;  // where a corrupt file was moved to
};

// No file: empty result. A corrupt file is renamed to "<name>.corrupt-<time>" (never
// overwritten, never deleted) and reported in `problem`; the caller starts a fresh session.
LoadResult load_session(const std::filesystem::path& path);

}  // namespace app
