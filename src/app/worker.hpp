// Runs PlaneSearch::submit() off the UI thread: the search is copied, the copy absorbs the
// choice and proposes the next plane, and the UI picks up the result when it is ready.
// A generation number lets the UI drop results it no longer wants (undo, start over).
#pragma once

#include <chrono>
#include <future>
#include <optional>
#include <string>

#include "app/session.hpp"
#include "sps/plane_search.hpp"

namespace app {

class SubmitWorker {
 public:
  struct Result {
    std::optional<sps::PlaneSearch> search;  // empty on failure
    std::string error;
    int generation = 0;
    double seconds = 0.0;
    // With holds: the next plane held and its first grid projected (Session::plane_preparer),
    // so the window thread only installs them.
    std::optional<PreparedPlane> prepared;
  };

  // Starts computing; only one job at a time (returns false if one is running).
  // `delay` (testing only) holds the job back, to show that the UI stays live meanwhile.
  // `vet` (Session::plane_vetter(); may be empty) and then `prepare`
  // (Session::plane_preparer(); may be empty) run after the optimizer, on the same thread.
  bool start(const sps::PlaneSearch& search, Submission submission, int generation,
             std::chrono::milliseconds delay = std::chrono::milliseconds(0),
             PlanePreparer prepare = {}, PlaneVetter vet = {});
  bool busy() const { return job_.valid(); }
  // The finished result, once; nullopt while running or idle.
  std::optional<Result> poll();
  // Blocks until the running job (if any) ends and returns its result.
  std::optional<Result> wait();

 private:
  std::future<Result> job_;
};

}  // namespace app
