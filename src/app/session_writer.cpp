#include "app/session_writer.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <utility>

namespace app {

SessionWriter::SessionWriter(FileStamp expected, std::chrono::milliseconds start_delay)
    : start_delay_(start_delay), expected_(expected), thread_([this] { run(); }) {}

SessionWriter::~SessionWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void SessionWriter::save(Session session, std::filesystem::path path) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (halted_) return;
    queued_.emplace(std::move(session), std::move(path));
  }
  wake_.notify_all();
}

void SessionWriter::flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  ++flushing_;
  wake_.notify_all();
  idle_.wait(lock, [this] { return !queued_ && !writing_; });
  --flushing_;
}

void SessionWriter::expect(FileStamp stamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  expected_ = stamp;
  halted_ = false;
}

std::optional<GuardedSave> SessionWriter::poll() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<GuardedSave> r = std::move(done_);
  done_.reset();
  return r;
}

void SessionWriter::run() {
  // Below the window's threads and the software renderer's: a long session's save takes tens
  // of milliseconds of CPU (about 60 at 50 planes), which on a machine with two cores came out
  // of the frames drawn right after the click that caused it. A failure leaves the priority.
  (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || queued_.has_value(); });
    if (!queued_) {
      if (stopping_) return;
      continue;
    }
    if (start_delay_.count() > 0 && !stopping_ && flushing_ == 0) {
      wake_.wait_for(lock, start_delay_, [this] { return stopping_ || flushing_ > 0; });
      if (!queued_) continue;
    }
    auto job = std::move(*queued_);
    queued_.reset();
    writing_ = true;
    const FileStamp expected = expected_;
    lock.unlock();
    GuardedSave result = save_session_guarded(job.first, job.second, expected);
    lock.lock();
    writing_ = false;
    expected_ = result.stamp;
    // After a conflict nothing more is written: the newer file is someone else's.
    if (result.conflict) {
      queued_.reset();
      halted_ = true;
    }
    done_ = std::move(result);
    idle_.notify_all();
    if (stopping_ && !queued_) return;
  }
}

}  // namespace app
