// Session files: where they live, atomic autosave, and loading that never loses a file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "app/session.hpp"

namespace app {

// $XDG_STATE_HOME/sequential-gallery/session.json, else ~/.local/state/sequential-gallery/...
std::filesystem::path default_session_path();

// Validates the session by reading its own JSON back before writing anything (a session that
// could not be read back is never written: the last good file stays), then writes it with the
// project's atomic writer (util/atomic_file.hpp), creating the folder if needed. Throws
// std::runtime_error naming the file and the reason (e.g. disk full); the old file is intact.
void save_session(const Session& session, const std::filesystem::path& path);

// How many set-aside copies of a session are kept: <name>.previous (newest), then
// <name>.previous.1 ... <name>.previous.4 (oldest); older ones are deleted.
constexpr int kKeptPreviousSessions = 5;

// Moves the session file aside as <name>.previous, shifting the older copies down one place
// (see kKeptPreviousSessions). Returns where the file went; throws std::runtime_error if it
// could not be moved (the file is then left where it is).
std::filesystem::path set_aside_session(const std::filesystem::path& path);

// What identifies one version of a file on disk: every atomic save makes a new inode, so a file
// replaced by another program (another window's autosave) has a different stamp even when its
// size and time agree.
struct FileStamp {
  bool exists = false;
  std::uintmax_t device = 0, inode = 0, size = 0;
  long long modified_ns = 0;
  bool operator==(const FileStamp& o) const {
    return exists == o.exists && device == o.device && inode == o.inode && size == o.size &&
           modified_ns == o.modified_ns;
  }
  bool operator!=(const FileStamp& o) const { return !(*this == o); }
};
FileStamp stamp_of(const std::filesystem::path& path);

// A name beside `path` for a copy set aside, "<path>.<tag>-<unix seconds>" (with "-1", "-2"...
// when that exists): corrupt files, conflict copies. Nothing is ever replaced by it.
std::filesystem::path unused_name_beside(const std::filesystem::path& path, const std::string& tag);

// save_session() unless the file at `path` was replaced since this program last read or wrote
// it (its stamp differs from `expected` and it exists): then the newer file is left as it is
// and `session` goes beside it as "<name>.conflict-<time>". Never throws.
struct GuardedSave {
  bool saved = false;     // written to `path`
  bool conflict = false;  // `path` was newer; see `beside`
  std::filesystem::path beside;
  std::string error;  // why nothing (or only the copy beside) was written
  FileStamp stamp;    // the file at `path` afterwards
};
GuardedSave save_session_guarded(const Session& session, const std::filesystem::path& path,
                                 const FileStamp& expected);

struct LoadResult {
  std::optional<Session> session;  // set when the file existed and was valid
  std::string problem;             // non-empty when the file was unreadable or corrupt
  // Non-empty when only the file's redo part was unusable ("<file>: redo[2]: ..."): the
  // session loaded without its redo stack.
  std::string redo_problem;
  std::filesystem::path set_aside;  // where a corrupt file was moved to
  FileStamp stamp;                  // the file as it was read
};

// No file: empty result. With `move_corrupt_aside` false (a window that only views a session
// another window has open) a corrupt file is only reported. Otherwise a corrupt file is renamed to
// "<name>.corrupt-<time>" (never overwritten, never deleted) and reported in `problem`; the caller
// starts a fresh session.
LoadResult load_session(const std::filesystem::path& path, bool move_corrupt_aside = true);

// Reads and parses a session file without touching it (session-info, tests). Throws
// std::runtime_error "<file>: <problem>" when it is missing, unreadable or unusable.
Session read_session_file(const std::filesystem::path& path);

// Whether the last save_session() through autosave failed (and why): the window shows a
// persistent warning until a save succeeds again.
class AutosaveStatus {
 public:
  void succeeded() { error_.clear(); }
  void failed(std::string error) { error_ = std::move(error); }
  bool failing() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  std::string error_;
};

}  // namespace app
