// Bradley-Terry-Luce likelihood of preference data given latent goodness values f:
// P(chosen > others) = exp(f_c / s) / sum_{j in {c} + others} exp(f_j / s).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sps/preference_data.hpp"

namespace sps {

// Log-likelihood of all preferences; fills the gradient (N) and, if `neg_hessian` is not
// null, the negated Hessian (N x N, positive semi-definite).
double btl_log_likelihood(const std::vector<Preference>& preferences, const Eigen::VectorXd& f,
                          double scale, Eigen::VectorXd* gradient = nullptr,
                          Eigen::MatrixXd* neg_hessian = nullptr);

}  // namespace sps
