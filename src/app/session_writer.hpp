// Autosave off the window thread: serializing a long session and reading it back costs tens of
// milliseconds (about 55 ms at 48 planes), which a click should not wait for. The window hands
// over a copy of the session after each change; one thread writes the newest copy (older ones
// still queued are skipped: the newest holds all they hold) with save_session_guarded(), so a
// file another window replaced is never written over.
#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "app/session.hpp"
#include "app/session_store.hpp"

namespace app {

class SessionWriter {
 public:
  // `expected`: the file as the caller last read it (its stamp), for the first save's check.
  // `start_delay`: how long a queued copy waits before it is written (a newer copy queued
  // meanwhile replaces it; flush() and the destructor do not wait).
  explicit SessionWriter(FileStamp expected,
                         std::chrono::milliseconds start_delay = std::chrono::milliseconds(0));
  ~SessionWriter();  // writes what is queued, then stops
  SessionWriter(const SessionWriter&) = delete;
  SessionWriter& operator=(const SessionWriter&) = delete;

  // Queues `session` for `path`, replacing a copy queued and not yet started. After a conflict
  // (the file was replaced by another program) nothing more is written until expect().
  void save(Session session, std::filesystem::path path);
  // Waits until everything queued is written.
  void flush();
  // After the caller changed the file itself (moved it aside), with the writer flushed: what
  // the next save expects to find.
  void expect(FileStamp stamp);
  // The outcome of the newest save finished since the last call, if any.
  std::optional<GuardedSave> poll();

 private:
  void run();

  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::optional<std::pair<Session, std::filesystem::path>> queued_;
  bool writing_ = false;
  bool stopping_ = false;
  int flushing_ = 0;  // flush() calls waiting: no start delay
  std::chrono::milliseconds start_delay_;
  bool halted_ = false;  // a conflict: the file is someone else's now
  FileStamp expected_;
  std::optional<GuardedSave> done_;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace app
