#include "sps/btl_likelihood.hpp"

#include <cmath>

namespace sps {

double btl_log_likelihood(const std::vector<Preference>& preferences, const Eigen::VectorXd& f,
                          double scale, Eigen::VectorXd* gradient, Eigen::MatrixXd* neg_hessian) {
  const Eigen::Index n = f.size();
  if (gradient != nullptr) gradient->setZero(n);
  if (neg_hessian != nullptr) neg_hessian->setZero(n, n);
  double total = 0.0;
  std::vector<int> members;
  std::vector<double> prob;
  for (const Preference& p : preferences) {
    members.assign(1, p.chosen);
    members.insert(members.end(), p.others.begin(), p.others.end());
    // Stable log-sum-exp.
    double max_z = -INFINITY;
    for (int j : members) max_z = std::max(max_z, f(j) / scale);
    double sum = 0.0;
    prob.resize(members.size());
    for (std::size_t m = 0; m < members.size(); ++m) {
      prob[m] = std::exp(f(members[m]) / scale - max_z);
      sum += prob[m];
    }
    total += f(p.chosen) / scale - (max_z + std::log(sum));
    for (double& q : prob) q /= sum;
    if (gradient != nullptr) {
      (*gradient)(p.chosen) += 1.0 / scale;
      for (std::size_t m = 0; m < members.size(); ++m) (*gradient)(members[m]) -= prob[m] / scale;
    }
    if (neg_hessian != nullptr) {
      const double inv_s2 = 1.0 / (scale * scale);
      for (std::size_t a = 0; a < members.size(); ++a) {
        (*neg_hessian)(members[a], members[a]) += prob[a] * inv_s2;
        for (std::size_t b = 0; b < members.size(); ++b) {
          (*neg_hessian)(members[a], members[b]) -= prob[a] * prob[b] * inv_s2;
        }
      }
    }
  }
  return total;
}

}  // namespace sps
