// Gaussian-process preference model: latent goodness f at the observed points with prior
// N(0, K_theta + b I) (ARD Matern 5/2 K, small white-noise term b), BTL likelihood of the
// preferences, and MAP estimation of f and the kernel hyperparameters theta under log-normal
// priors (Koyama et al. 2017/2020). Predictions treat the MAP f as noisy observations.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sps/matern_kernel.hpp"
#include "sps/preference_data.hpp"

namespace sps {

struct ModelSettings {
  // Median of the log-normal prior on the amplitude. The paper uses 0.2; 0.4 (a sharper
  // likelihood relative to the prior) gave clearly lower gaps in every benchmark setting
  // (docs/benchmarks.md).
  double amplitude_prior = 0.4;
  double length_scale_prior = 0.5;   // median of the log-normal prior on each length scale
  double prior_log_variance = 0.01;  // variance of both priors in log space
  double btl_scale = 0.01;           // temperature s of the BTL likelihood
  double noise_variance = 1e-6;      // b: white noise on the latent values (keeps C regular)
  int max_hyper_iterations = 40;     // L-BFGS-B iterations for the hyperparameters
  // The model uses the newest preferences whose points number at most this many, so that a
  // long session stays responsive (the cost grows with the cube of the point count).
  int max_points = 300;
  // Empty, or one factor per dimension: the prior median of length scale k becomes
  // length_scale_prior * factor_k. Perceptual scaling sets it so that a direction that changes
  // what the user sees faster gets a shorter length scale (PlaneSearch::set_perceptual_scale).
  Eigen::VectorXd length_scale_factors;

  // Log-space prior mean of each hyperparameter [log a, log l_1..l_d].
  Eigen::VectorXd prior_log_mean(int dims) const;
};

// The MAP objective as a function of the log hyperparameters, with f maximized out
// (the profile). By the envelope theorem its gradient equals the partial gradient of the
// joint objective at the inner optimum, which is what makes this cheap.
// The part of the data the model is fitted to: everything, or the newest preferences that fit
// within settings.max_points points (re-indexed, original order kept).
PreferenceData model_window(const PreferenceData& data, const ModelSettings& settings);

class MapObjective {
 public:
  MapObjective(const PreferenceData& data, const ModelSettings& settings);

  // Returns the objective at theta and fills `gradient`; `f` is the warm start for the inner
  // Newton solve and receives the optimal latent values.
  double evaluate(const Eigen::VectorXd& log_theta, Eigen::VectorXd& f,
                  Eigen::VectorXd& gradient) const;
  // The joint objective log p(D|f) + log N(f; 0, C) + log p(theta) at fixed f (for tests).
  double joint(const Eigen::VectorXd& log_theta, const Eigen::VectorXd& f) const;
  // Inner problem: maximizes over f at fixed theta (Newton with step halving).
  Eigen::VectorXd optimal_latent(const Eigen::VectorXd& log_theta, Eigen::VectorXd f) const;

 private:
  const PreferenceData& data_;
  ModelSettings settings_;
};

class PreferenceModel {
 public:
  // An empty model (no data): prior mean 0, prior variance.
  PreferenceModel(int dims, const ModelSettings& settings);
  // A model at given hyperparameters and latent values (no optimization); `latent` belongs to
  // the points of model_window(data, settings).
  PreferenceModel(const PreferenceData& data, const ModelSettings& settings, KernelParams params,
                  Eigen::VectorXd latent);

  // MAP fit, warm-started from `warm_params` and `warm_latent` (size <= point count; missing
  // entries are predicted by `previous`).
  static PreferenceModel fit(const PreferenceData& data, const ModelSettings& settings,
                             const PreferenceModel& previous);

  int dims() const { return dims_; }
  int point_count() const { return static_cast<int>(points_.cols()); }
  const KernelParams& params() const { return kernel_.params(); }
  const Eigen::VectorXd& latent() const { return latent_; }
  const Eigen::MatrixXd& points() const { return points_; }

  double mean(const Eigen::VectorXd& x) const;
  double variance(const Eigen::VectorXd& x) const;
  // Mean and variance with their gradients w.r.t. x.
  void predict(const Eigen::VectorXd& x, double& mean, double& variance, Eigen::VectorXd* d_mean,
               Eigen::VectorXd* d_variance) const;

  // The same for the columns of xs (d x m), using matrix-matrix products.
  void predict_batch(const Eigen::MatrixXd& xs, Eigen::VectorXd& mean, Eigen::VectorXd& variance,
                     Eigen::MatrixXd* d_mean, Eigen::MatrixXd* d_variance) const;

  // Index (into points()) of the observed point with the largest posterior mean (-1 without data).
  int best_observed_index() const;

 private:
  int dims_;
  MaternKernel kernel_;
  Eigen::MatrixXd points_;  // d x N
  Eigen::VectorXd latent_;  // MAP f
  Eigen::VectorXd alpha_;   // C^-1 f
  Eigen::MatrixXd c_inv_;   // C^-1
};

}  // namespace sps
