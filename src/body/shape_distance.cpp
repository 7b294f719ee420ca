#include "body/shape_distance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace body {

namespace {

constexpr float kMmPerUnitX = 6000.0f;  // beta = 6x - 3; model units are metres

void check_size(const Eigen::VectorXd& x, int dims) {
  if (x.size() != dims) {
    throw std::invalid_argument("shape distance: a search point has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(dims));
  }
}

}  // namespace

ShapeDistance::ShapeDistance(const Model& model) {
  if (model.vertex_count() == 0 || model.shapedirs.rows() != 3 * model.vertex_count()) {
    throw std::invalid_argument("shape distance: the model '" + model.name +
                                "' has no vertices or mismatched shape directions");
  }
  unit_dirs_mm_ = kMmPerUnitX * model.shapedirs;
}

Eigen::VectorXf ShapeDistance::displacement_mm(const Eigen::VectorXd& x,
                                               const Eigen::VectorXd& origin) const {
  check_size(x, dims());
  check_size(origin, dims());
  return unit_dirs_mm_ * (x - origin).cast<float>();
}

Eigen::VectorXf vertex_norms(const Eigen::VectorXf& displacement) {
  const Eigen::Index v = displacement.size() / 3;
  Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>> d(displacement.data(),
                                                                               v, 3);
  return d.rowwise().norm();
}

double ShapeDistance::rms_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  const Eigen::VectorXf d = displacement_mm(a, b);
  return std::sqrt(static_cast<double>(d.squaredNorm()) / static_cast<double>(vertex_count()));
}

double ShapeDistance::max_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  return static_cast<double>(vertex_norms(displacement_mm(a, b)).maxCoeff());
}

namespace {

// x_target = (beta + 3) / 6 may lie outside the box; the difference is all that matters.
Eigen::VectorXd target_point(const Eigen::VectorXf& target_betas, int dims) {
  if (target_betas.size() != dims) {
    throw std::invalid_argument("shape distance: the target has " +
                                std::to_string(target_betas.size()) + " betas, the model " +
                                std::to_string(dims));
  }
  return (target_betas.cast<double>().array() + 3.0) / 6.0;
}

}  // namespace

std::vector<double> ShapeDistance::to_betas_mm(
    const std::vector<Eigen::VectorXd>& xs, const Eigen::VectorXf& target_betas,
    double (ShapeDistance::*distance)(const Eigen::VectorXd&, const Eigen::VectorXd&) const) const {
  const Eigen::VectorXd target = target_point(target_betas, dims());
  std::vector<double> out;
  out.reserve(xs.size());
  for (const auto& x : xs) out.push_back((this->*distance)(x, target));
  return out;
}

std::vector<double> ShapeDistance::rms_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                                   const Eigen::VectorXf& target_betas) const {
  return to_betas_mm(xs, target_betas, &ShapeDistance::rms_mm);
}

std::vector<double> ShapeDistance::max_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                                   const Eigen::VectorXf& target_betas) const {
  return to_betas_mm(xs, target_betas, &ShapeDistance::max_mm);
}

namespace {

// The largest norm of the listed vertices of a 3V displacement.
double largest_of(const Eigen::VectorXf& displacement, const std::vector<int>& vertices) {
  float largest = 0.0f;
  for (const int v : vertices) {
    largest = std::max(largest, displacement.segment<3>(3 * static_cast<Eigen::Index>(v)).norm());
  }
  return static_cast<double>(largest);
}

void check_vertices(const std::vector<int>& vertices, int count) {
  for (const int v : vertices) {
    if (v < 0 || v >= count) {
      throw std::invalid_argument("shape distance: vertex " + std::to_string(v) +
                                  " is not one of the model's " + std::to_string(count));
    }
  }
}

}  // namespace

std::vector<double> ShapeDistance::max_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                                   const Eigen::VectorXf& target_betas,
                                                   const std::vector<int>& vertices) const {
  check_vertices(vertices, vertex_count());
  const Eigen::VectorXd target = target_point(target_betas, dims());
  std::vector<double> out;
  out.reserve(xs.size());
  for (const auto& x : xs) out.push_back(largest_of(displacement_mm(x, target), vertices));
  return out;
}

Eigen::MatrixXf ShapeDistance::displacements_from_first(
    const std::vector<Eigen::VectorXd>& xs) const {
  const Eigen::Index n = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXf diffs(dims(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    check_size(xs[static_cast<std::size_t>(i)], dims());
    diffs.col(i) = (xs[static_cast<std::size_t>(i)] - xs.front()).cast<float>();
  }
  return unit_dirs_mm_ * diffs;
}

Eigen::MatrixXd ShapeDistance::pairwise_max_mm(const std::vector<Eigen::VectorXd>& xs,
                                               const std::vector<int>& vertices) const {
  check_vertices(vertices, vertex_count());
  const Eigen::Index n = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  if (n == 0) return out;
  const Eigen::MatrixXf disp = displacements_from_first(xs);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      float largest = 0.0f;
      for (const int v : vertices) {
        const Eigen::Index r = 3 * static_cast<Eigen::Index>(v);
        largest = std::max(largest, (disp.col(i).segment<3>(r) - disp.col(j).segment<3>(r)).norm());
      }
      out(i, j) = static_cast<double>(largest);
      out(j, i) = out(i, j);
    }
  }
  return out;
}

Eigen::MatrixXd ShapeDistance::pairwise_max_mm(const std::vector<Eigen::VectorXd>& xs) const {
  const Eigen::Index n = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  if (n == 0) return out;
  const Eigen::MatrixXf disp = displacements_from_first(xs);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const double d = static_cast<double>(vertex_norms(disp.col(i) - disp.col(j)).maxCoeff());
      out(i, j) = d;
      out(j, i) = d;
    }
  }
  return out;
}

Eigen::VectorXd ShapeDistance::direction_rms_mm() const {
  Eigen::VectorXd out(dims());
  for (int k = 0; k < dims(); ++k) {
    out(k) = std::sqrt(static_cast<double>(unit_dirs_mm_.col(k).squaredNorm()) /
                       static_cast<double>(vertex_count()));
  }
  return out;
}

Eigen::MatrixXd ShapeDistance::direction_gram_mm2() const {
  const Eigen::MatrixXd dirs = unit_dirs_mm_.cast<double>();
  Eigen::MatrixXd gram = dirs.transpose() * dirs / static_cast<double>(vertex_count());
  return 0.5 * (gram + gram.transpose());
}

}  // namespace body
