#include "app/session_store.hpp"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <sys/stat.h>

#include "util/atomic_file.hpp"
#include "util/file_read.hpp"

namespace app {

namespace fs = std::filesystem;

fs::path default_session_path() {
  fs::path base;
  if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg != nullptr && xdg[0] == '/') {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0') {
    base = fs::path(home) / ".local" / "state";
  } else {
    base = fs::temp_directory_path();
  }
  return base / "sequential-gallery" / "session.json";
}

void save_session(const Session& session, const fs::path& path) {
  const std::string text = session.to_json();
  try {
    const Session back = Session::from_json(text);
    if (!back.redo_problem().empty()) throw std::runtime_error(back.redo_problem());
  } catch (const std::exception& e) {
    throw std::runtime_error(
        "did not save " + path.string() +
        " (kept the last good file): the session failed its own check: " + e.what());
  }
  try {
    util::write_file_atomically(path, text, /*create_folders=*/true);
  } catch (const util::FileWriteError& e) {
    throw std::runtime_error(std::string("cannot save the session: ") + e.what());
  }
}

namespace {

fs::path previous_name(const fs::path& path, int index) {
  fs::path p = path;
  p += ".previous";
  if (index > 0) p += "." + std::to_string(index);
  return p;
}

}  // namespace

fs::path set_aside_session(const fs::path& path) {
  std::error_code ec;
  // Shift .previous.3 -> .previous.4, ..., .previous -> .previous.1; the oldest is replaced.
  for (int i = kKeptPreviousSessions - 2; i >= 0; --i) {
    const fs::path from = previous_name(path, i);
    if (fs::exists(from, ec)) fs::rename(from, previous_name(path, i + 1), ec);
  }
  const fs::path aside = previous_name(path, 0);
  fs::rename(path, aside, ec);
  if (ec) {
    throw std::runtime_error("could not move " + path.string() + " to " + aside.string() + ": " +
                             ec.message());
  }
  return aside;
}

namespace {

// Reads the whole file; returns a problem text (empty when fine). A session is a few megabytes
// at most; a huge file, a pipe or a device is refused before anything is read.
std::string read_session_text(const fs::path& path, std::string& text) {
  constexpr std::size_t kMaxBytes = 256u << 20;
  try {
    text = util::read_regular_file(path, kMaxBytes);
  } catch (const util::FileReadError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

Session read_session_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error(path.string() + ": no such file");
  std::string text;
  if (const std::string problem = read_session_text(path, text); !problem.empty()) {
    throw std::runtime_error(problem);
  }
  try {
    return Session::from_json(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

FileStamp stamp_of(const fs::path& path) {
  FileStamp stamp;
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return stamp;
  stamp.exists = true;
  stamp.device = st.st_dev;
  stamp.inode = st.st_ino;
  stamp.size = static_cast<std::uintmax_t>(st.st_size);
  stamp.modified_ns = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  return stamp;
}

fs::path unused_name_beside(const fs::path& path, const std::string& tag) {
  const auto stamp = std::chrono::duration_cast<std::chrono::seconds>(
                         std::chrono::system_clock::now().time_since_epoch())
                         .count();
  const std::string base = path.string() + "." + tag + "-" + std::to_string(stamp);
  fs::path name = base;
  std::error_code ec;
  // symlink_status: a dangling link there is a name in use too.
  for (int i = 1; fs::exists(fs::symlink_status(name, ec)); ++i) {
    name = base + "-" + std::to_string(i);
  }
  return name;
}

GuardedSave save_session_guarded(const Session& session, const fs::path& path,
                                 const FileStamp& expected) {
  GuardedSave result;
  if (const FileStamp now = stamp_of(path); now.exists && now != expected) {
    result.conflict = true;
    result.stamp = now;
    result.beside = unused_name_beside(path, "conflict");
    try {
      save_session(session, result.beside);
    } catch (const std::exception& e) {
      result.error = e.what();
      result.beside.clear();
    }
    return result;
  }
  try {
    save_session(session, path);
    result.saved = true;
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  result.stamp = stamp_of(path);
  return result;
}

LoadResult load_session(const fs::path& path, bool move_corrupt_aside) {
  LoadResult result;
  std::error_code ec;
  if (!fs::exists(path, ec)) return result;
  result.stamp = stamp_of(path);
  std::string text;
  if (std::string problem = read_session_text(path, text); !problem.empty()) {
    result.problem = "cannot read session " + problem;
    return result;  // unreadable (permissions?): leave it where it is
  }
  try {
    result.session = Session::from_json(text);
    if (!result.session->redo_problem().empty()) {
      result.redo_problem = "session file " + path.string() + ": " +
                            result.session->redo_problem() +
                            "; resumed without the steps Redo would bring back";
    }
    return result;
  } catch (const std::exception& e) {
    if (!move_corrupt_aside) {
      result.problem = "session file " + path.string() + " is corrupt: " + e.what();
      return result;
    }
    const fs::path aside = unused_name_beside(path, "corrupt");
    fs::rename(path, aside, ec);
    result.problem = "session file " + path.string() + " is corrupt: " + e.what();
    if (ec) {
      result.problem += "; could not move it aside (" + ec.message() + "), left in place";
    } else {
      result.set_aside = aside;
      result.problem += "; moved it to " + aside.string() + " and started a new session";
    }
    return result;
  }
}

}  // namespace app
