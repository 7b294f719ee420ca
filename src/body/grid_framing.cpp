#include "body/grid_framing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace body {

GridFraming::GridFraming(const Model& model) : heights_(model) {
  const Eigen::Index v = model.vertex_count();
  if (v == 0 || model.shapedirs.rows() != 3 * v) {
    throw std::invalid_argument("grid framing: the model '" + model.name +
                                "' has no vertices or mismatched shape directions");
  }
  // beta = 6x - 3: the template less 3 of every kept direction is the body at x = 0.
  unit_dirs_ = 6.0f * model.shapedirs;
  template_ = Eigen::Map<const Eigen::VectorXf>(model.v_template.data(), 3 * v) -
              3.0f * model.shapedirs.rowwise().sum();
}

namespace {

Eigen::VectorXd mean_point(const std::vector<Eigen::VectorXd>& xs, int dims) {
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(dims);
  for (const auto& x : xs) {
    if (x.size() != dims) {
      throw std::invalid_argument("grid framing: a search point has " + std::to_string(x.size()) +
                                  " entries, the model " + std::to_string(dims));
    }
    mean += x;
  }
  return xs.empty() ? mean : Eigen::VectorXd(mean / static_cast<double>(xs.size()));
}

}  // namespace

FramedBand GridFraming::frame(const std::vector<Eigen::VectorXd>& xs, const BandRule& rule) const {
  // The mean body's heights above its lowest vertex.
  const Eigen::VectorXf body = template_ + unit_dirs_ * mean_point(xs, dims()).cast<float>();
  Eigen::VectorXf y(body.size() / 3);
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = body[3 * i + 1];
  y = (y.array() - y.minCoeff()).matrix();
  FramedBand framed;
  framed.tallest_m = heights_.tallest_m(xs);
  framed.band = band_on(y, framed.tallest_m, xs, rule);
  for (Eigen::Index v = 0; v < y.size(); ++v) {
    const double h = static_cast<double>(y[v]);
    if (h >= framed.band.bottom_m && h <= framed.band.top_m) {
      framed.vertices.push_back(static_cast<int>(v));
    }
  }
  return framed;
}

HeightBand GridFraming::band_on(const Eigen::VectorXf& y, double tallest_m,
                                const std::vector<Eigen::VectorXd>& xs,
                                const BandRule& rule) const {
  const double height = static_cast<double>(y.maxCoeff());
  const double margin = std::max(0.0, rule.margin_m);
  const HeightBand whole{-margin, tallest_m + margin};
  if (xs.size() < 2) return whole;
  const Eigen::VectorXd mean = mean_point(xs, dims());
  Eigen::MatrixXf offsets(dims(), static_cast<Eigen::Index>(xs.size()));
  for (std::size_t i = 0; i < xs.size(); ++i) {
    offsets.col(static_cast<Eigen::Index>(i)) = (xs[i] - mean).cast<float>();
  }
  const Eigen::MatrixXf disp = unit_dirs_ * offsets;  // 3V x n, from the mean body
  // How far each vertex moves across the grid: its largest distance from the mean body's.
  Eigen::VectorXf moves = Eigen::VectorXf::Zero(y.size());
  for (Eigen::Index v = 0; v < y.size(); ++v) {
    moves[v] = disp.middleRows(3 * v, 3).colwise().norm().maxCoeff();
  }
  const float largest = moves.maxCoeff();
  if (!(largest > 0.0f)) return whole;
  float low = y.maxCoeff();
  const float cut = static_cast<float>(std::clamp(rule.share, 0.0, 1.0)) * largest;
  for (Eigen::Index v = 0; v < y.size(); ++v) {
    if (moves[v] >= cut) low = std::min(low, y[v]);
  }
  // The band runs up to the top of the tallest head: a face cut by the frame's edge, or a
  // grid of legs without their people, would draw the eye more than the difference. It goes
  // down to the lowest vertex that moves that much, at least rule.min_height_m, and to the
  // floor once it reaches the shins.
  HeightBand band{std::min(static_cast<double>(low) - margin, whole.top_m - rule.min_height_m),
                  whole.top_m};
  if (band.bottom_m < rule.feet_share * height) band.bottom_m = whole.bottom_m;
  if (band.bottom_m <= whole.bottom_m) return whole;
  return band;
}

}  // namespace body
