#include "app/session_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

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

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what, int err) {
  throw std::runtime_error("cannot save " + path.string() + ": " + what + " (" +
                           std::strerror(err) + ")");
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& text) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) fail(path, "cannot create directory " + dir.string(), ec.value());
  const fs::path tmp =
      dir / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "cannot create " + tmp.string(), errno);
  const char* data = text.data();
  size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      fail(path, "write failed", err);
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail(path, "flush failed", err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail(path, "rename failed", err);
  }
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void save_session(const Session& session, const fs::path& path) {
  write_file_atomically(path, session.to_json());
}

LoadResult load_session(const fs::path& path) {
  LoadResult result;
  std::error_code ec;
  if (!fs::exists(path, ec)) return result;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in) {
    result.problem = "cannot read session " + path.string() + ": " + std::strerror(errno);
    return result;  // unreadable (permissions?): leave it where it is
  }
  try {
    result.session = Session::from_json(text.str());
    return result;
  } catch (const std::exception& e) {
    const auto stamp = std::chrono::duration_cast<std::chrono::seconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
    fs::path aside = path;
    aside += ".corrupt-" + std::to_string(stamp);
    for (int i = 1; fs::exists(aside, ec); ++i) {
      aside = path;
      aside += ".corrupt-" + std::to_string(stamp) + "-" + std::to_string(i);
    }
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
