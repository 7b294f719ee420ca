// Expected improvement over the current best posterior mean, and its maximization over the
// unit box (multi-start bounded L-BFGS-B), or over the part of a tangent plane inside it when
// some quantities are held (sps/tangent_space.hpp).
#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>

#include "sps/preference_model.hpp"
#include "sps/tangent_space.hpp"

namespace sps {

// EI(x) = (mu - mu+) Phi(z) + sigma phi(z), z = (mu - mu+) / sigma (maximization form; the
// paper's appendix prints gamma with the sign flipped). Fills the gradient if requested.
double expected_improvement(const PreferenceModel& model, const Eigen::VectorXd& x,
                            double best_mean, Eigen::VectorXd* gradient = nullptr);

// EI at the columns of xs (d x m); gradients as columns of `gradient` if requested.
Eigen::VectorXd expected_improvement_batch(const PreferenceModel& model, const Eigen::MatrixXd& xs,
                                           double best_mean, Eigen::MatrixXd* gradient = nullptr);

struct EiSearchSettings {
  int candidates = 0;  // random candidates scored before local search; 0 = automatic
  int starts = 0;      // local searches from the best candidates; 0 = automatic
  int max_iterations = 60;
  int threads = 2;
};

// argmax EI over the points x+ + P (y - x+) inside [0,1]^d (P: `space`'s projector; y in the
// box, clamped where the map leaves it): the whole box for the whole space. `x_plus` and the
// observed points seed the candidates too, each mapped onto that plane.
Eigen::VectorXd maximize_expected_improvement(const PreferenceModel& model, double best_mean,
                                              const Eigen::VectorXd& x_plus, std::mt19937_64& rng,
                                              const EiSearchSettings& settings,
                                              const TangentSpace& space = {});

// The indices of the (at most) `count` observed points with the largest posterior means, best
// first (ties by index): the starts of the searches for the posterior-mean maximum.
std::vector<int> best_observed_points(const PreferenceModel& model, int count);

// argmax of the posterior mean over [0,1]^d by local searches from the observed points with
// the largest means (the model's best estimate, which may lie between observations). Returns
// `fallback` when the model has no data.
Eigen::VectorXd maximize_posterior_mean(const PreferenceModel& model,
                                        const Eigen::VectorXd& fallback, int starts = 4,
                                        int max_iterations = 60, int threads = 2);

// argmax of the posterior mean over the tangent plane through `anchor` (a point of the held
// surface), from the anchor and the observed points with the largest means mapped onto that
// plane. The anchor without data.
Eigen::VectorXd maximize_posterior_mean_on_tangent(const PreferenceModel& model,
                                                   const Eigen::VectorXd& anchor,
                                                   const TangentSpace& space, int starts,
                                                   int threads);

}  // namespace sps
