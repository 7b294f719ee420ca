#include "rig.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Cholesky>

namespace default_model {

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, Vec3* closest) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Vec3 c = a + t * ab;
  if (closest) *closest = c;
  return (p - c).norm();
}

Eigen::MatrixXd skin_weights(const std::vector<Vec3>& vertices, const Skeleton& skeleton,
                             double softness, int max_influences) {
  const int V = static_cast<int>(vertices.size());
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V, kJointCount);
  for (int v = 0; v < V; ++v) {
    std::array<double, kJointCount> d;
    for (int j = 0; j < kJointCount; ++j)
      d[j] = segment_distance(vertices[v], skeleton.bone_start[j], skeleton.bone_end[j]) /
             skeleton.bone_radius[j];
    const double dmin = *std::min_element(d.begin(), d.end());
    std::array<double, kJointCount> w;
    for (int j = 0; j < kJointCount; ++j) {
      const double x = (d[j] - dmin) / softness;
      w[j] = x < 4.0 ? std::exp(-x * x) : 0.0;
    }
    if (max_influences > 0 && max_influences < kJointCount) {
      std::array<int, kJointCount> order;
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return w[a] > w[b]; });
      for (int k = max_influences; k < kJointCount; ++k) w[order[k]] = 0.0;
    }
    const double sum = std::accumulate(w.begin(), w.end(), 0.0);
    for (int j = 0; j < kJointCount; ++j) W(v, j) = w[j] / sum;
  }
  return W;
}

double convex_joint_weights(const std::vector<Vec3>& vertices, const Vec3& c,
                            const std::vector<int>& candidates, double radius,
                            std::vector<std::pair<int, double>>* out) {
  std::vector<int> idx;
  std::vector<double> prior;
  for (int v : candidates) {
    const double r = (vertices[v] - c).norm();
    if (r < radius) {
      idx.push_back(v);
      const double x = r / (0.6 * radius);
      prior.push_back(std::exp(-x * x));
    }
  }
  out->clear();
  if (idx.empty()) return 1e9;
  // Maximum entropy tilt: p_i ~ prior_i exp(lambda . (v_i - c)) with sum p_i (v_i - c) = 0.
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
  std::vector<double> p(idx.size());
  for (int it = 0; it < 60; ++it) {
    double m = -1e300;
    std::vector<double> e(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i) {
      e[i] = lambda.dot(vertices[idx[i]] - c);
      m = std::max(m, e[i]);
    }
    double z = 0;
    for (std::size_t i = 0; i < idx.size(); ++i) z += p[i] = prior[i] * std::exp(e[i] - m);
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < idx.size(); ++i) {
      p[i] /= z;
      const Vec3 d = vertices[idx[i]] - c;
      g += p[i] * d;
      H += p[i] * d * d.transpose();
    }
    H -= g * g.transpose();
    if (g.norm() < 1e-9) break;
    Eigen::Vector3d step = H.ldlt().solve(g);
    // Damped Newton: never move lambda by more than a safe amount per step.
    const double limit = 200.0;
    if (step.norm() > limit) step *= limit / step.norm();
    lambda -= step;
  }
  Vec3 fit = Vec3::Zero();
  for (std::size_t i = 0; i < idx.size(); ++i) {
    out->push_back({idx[i], p[i]});
    fit += p[i] * vertices[idx[i]];
  }
  return (fit - c).norm();
}

Eigen::MatrixXd joint_regressor(const std::vector<Vec3>& vertices, const Skeleton& skeleton) {
  const int V = static_cast<int>(vertices.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(kJointCount, V);
  std::vector<int> all(V);
  std::iota(all.begin(), all.end(), 0);
  std::vector<std::pair<int, double>> row;
  for (int j = 0; j < kJointCount; ++j) {
    const Vec3& c = skeleton.joints[j];
    double nearest = 1e9;
    for (const Vec3& p : vertices) nearest = std::min(nearest, (p - c).norm());
    convex_joint_weights(vertices, c, all, 1.8 * nearest + 0.015, &row);
    for (const auto& [v, w] : row) R(j, v) = w;
  }
  return R;
}

}  // namespace default_model
