#include "bench/simulated_person.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "app/worker.hpp"

namespace bench {

int jnd_pick(const std::vector<double>& distance_mm, double jnd_mm, std::mt19937_64& rng) {
  if (distance_mm.empty()) throw std::invalid_argument("jnd_pick: no cells");
  const double best = *std::min_element(distance_mm.begin(), distance_mm.end());
  std::vector<int> candidates;
  for (std::size_t i = 0; i < distance_mm.size(); ++i) {
    if (distance_mm[i] <= best + jnd_mm) candidates.push_back(static_cast<int>(i));
  }
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  return candidates[pick(rng)];
}

bool has_look_alikes(const Eigen::MatrixXd& pairwise_mm, double clone_mm) {
  for (Eigen::Index i = 0; i < pairwise_mm.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < pairwise_mm.cols(); ++j) {
      if (!(pairwise_mm(i, j) >= clone_mm)) return true;
    }
  }
  return false;
}

double pinned_fraction(const Eigen::VectorXd& x, double tolerance) {
  if (x.size() == 0) return 0.0;
  int pinned = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (std::abs(x[i]) <= tolerance || std::abs(1.0 - x[i]) <= tolerance) ++pinned;
  }
  return static_cast<double>(pinned) / static_cast<double>(x.size());
}

PlaneOutcome play_plane_jnd(app::Session& session, const TargetDistance& to_target,
                            const app::PairwiseDistance& look_alikes, double jnd_mm,
                            std::mt19937_64& rng, double clone_mm) {
  PlaneOutcome out;
  const int n = session.settings().grid_size;
  while (!session.submission_pending()) {
    std::vector<Eigen::VectorXd> xs;
    for (auto& p : session.cells()) xs.push_back(std::move(p.x));
    ++out.grids;
    for (const auto& x : xs) {
      ++out.cells;
      if (pinned_fraction(x) > 0.0) ++out.edge_cells;
    }
    if (look_alikes && has_look_alikes(look_alikes(xs), clone_mm)) ++out.look_alike_grids;
    const int index = jnd_pick(to_target(xs), jnd_mm, rng);
    if (session.click({index % n, index / n}) == app::ClickResult::kIgnored) {
      throw std::logic_error("the session ignored a click inside the grid");
    }
  }
  const app::Submission submission = session.submission();
  out.chosen = submission.chosen;
  app::SubmitWorker worker;
  worker.start(session.search(), submission, 0, std::chrono::milliseconds(0),
               session.plane_preparer(), session.plane_vetter());
  auto result = worker.wait();
  if (!result || !result->search) {
    throw std::runtime_error("the optimizer failed: " + (result ? result->error : "no result"));
  }
  out.optimizer_seconds = result->search->last_submit_seconds();
  session.finish_plane(std::move(*result->search), std::move(result->prepared));
  return out;
}

}  // namespace bench
