#include "app/worker.hpp"

#include <exception>
#include <thread>

namespace app {

bool SubmitWorker::start(const sps::PlaneSearch& search, Submission submission, int generation,
                         std::chrono::milliseconds delay, PlanePreparer prepare, PlaneVetter vet) {
  if (job_.valid()) return false;
  job_ = std::async(
      std::launch::async,
      [search = sps::PlaneSearch(search), submission = std::move(submission), generation, delay,
       prepare = std::move(prepare), vet = std::move(vet)]() mutable {
        Result result;
        result.generation = generation;
        const auto start = std::chrono::steady_clock::now();
        if (delay.count() > 0) std::this_thread::sleep_for(delay);
        try {
          search.submit(submission.chosen, submission.extra_comparisons, submission.representatives,
                        submission.set_directly);
          if (vet) {
            // Only a better plane where the new one looks alike: if that fails, the
            // optimizer's plane stands.
            try {
              vet(search);
            } catch (const std::exception&) {
            }
          }
          if (prepare) {
            // Only a head start for the window: if it fails, the window makes it itself
            // (and reports what went wrong there); the optimizer's result stands.
            try {
              result.prepared = prepare(search);
            } catch (const std::exception&) {
              result.prepared.reset();
            }
          }
          result.search = std::move(search);
        } catch (const std::exception& e) {
          result.error = e.what();
        }
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result;
      });
  return true;
}

std::optional<SubmitWorker::Result> SubmitWorker::poll() {
  if (!job_.valid()) return std::nullopt;
  if (job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
  return job_.get();
}

std::optional<SubmitWorker::Result> SubmitWorker::wait() {
  if (!job_.valid()) return std::nullopt;
  return job_.get();
}

}  // namespace app
