#include "sps/preference_data.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace sps {

PreferenceData::PreferenceData(int dims, double merge_distance)
    : dims_(dims), merge_distance_(merge_distance), points_(dims, 0) {
  if (dims < 1) throw std::invalid_argument("PreferenceData: dimension must be at least 1");
}

int PreferenceData::add_point(const Eigen::VectorXd& x) {
  if (x.size() != dims_) {
    throw std::invalid_argument("point has " + std::to_string(x.size()) + " entries, expected " +
                                std::to_string(dims_));
  }
  if (!x.allFinite()) throw std::invalid_argument("point has non-finite entries");
  const Eigen::VectorXd clamped = x.cwiseMax(0.0).cwiseMin(1.0);
  const double limit2 = merge_distance_ * merge_distance_;
  for (Eigen::Index i = 0; i < points_.cols(); ++i) {
    if ((points_.col(i) - clamped).squaredNorm() <= limit2) return static_cast<int>(i);
  }
  points_.conservativeResize(Eigen::NoChange, points_.cols() + 1);
  points_.col(points_.cols() - 1) = clamped;
  return static_cast<int>(points_.cols() - 1);
}

void PreferenceData::add_point_exact(const Eigen::VectorXd& x) {
  if (x.size() != dims_ || !x.allFinite() || (x.array() < 0.0).any() || (x.array() > 1.0).any()) {
    throw std::invalid_argument("a stored point is malformed or outside the unit box");
  }
  points_.conservativeResize(Eigen::NoChange, points_.cols() + 1);
  points_.col(points_.cols() - 1) = x;
}

bool PreferenceData::add_preference(const Eigen::VectorXd& chosen,
                                    const std::vector<Eigen::VectorXd>& others) {
  const int points_before = point_count();
  Preference p;
  p.chosen = add_point(chosen);
  for (const auto& o : others) {
    const int index = add_point(o);
    if (index != p.chosen && std::find(p.others.begin(), p.others.end(), index) == p.others.end()) {
      p.others.push_back(index);
    }
  }
  if (p.others.empty()) {
    truncate(points_before, preference_count());  // nothing learned; keep the data unchanged
    return false;
  }
  preferences_.push_back(std::move(p));
  return true;
}

void PreferenceData::add_preference_indices(Preference p) {
  const auto valid = [&](int i) { return i >= 0 && i < point_count(); };
  if (!valid(p.chosen) || p.others.empty() ||
      !std::all_of(p.others.begin(), p.others.end(), valid)) {
    throw std::invalid_argument("preference refers to a point that does not exist");
  }
  preferences_.push_back(std::move(p));
}

void PreferenceData::truncate(int points, int preferences) {
  if (points < 0 || points > point_count() || preferences < 0 || preferences > preference_count()) {
    throw std::invalid_argument("PreferenceData::truncate: out of range");
  }
  points_.conservativeResize(Eigen::NoChange, points);
  preferences_.resize(static_cast<std::size_t>(preferences));
}

}  // namespace sps
