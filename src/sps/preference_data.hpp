// Observed points and the preferences among them ("chosen > {others}"), append-only so that
// undo is a truncation. Near-duplicate points are merged: the data grows only with points
// that are actually new.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace sps {

struct Preference {
  int chosen = 0;
  std::vector<int> others;  // never contains `chosen`, no repeats
};

class PreferenceData {
 public:
  explicit PreferenceData(int dims, double merge_distance = 1e-6);

  int dims() const { return dims_; }
  int point_count() const { return static_cast<int>(points_.cols()); }
  int preference_count() const { return static_cast<int>(preferences_.size()); }
  const Eigen::MatrixXd& points() const { return points_; }  // d x N
  const std::vector<Preference>& preferences() const { return preferences_; }
  double merge_distance() const { return merge_distance_; }

  // Index of an existing point within the merge distance of x, or of x appended (clamped
  // into [0,1]^d first).
  int add_point(const Eigen::VectorXd& x);
  // Adds "chosen > others"; returns false (and adds nothing) if nothing distinct remains on
  // the right-hand side after merging.
  bool add_preference(const Eigen::VectorXd& chosen, const std::vector<Eigen::VectorXd>& others);
  // Deserialization: appends x as it is (no merging; must lie in the unit box).
  void add_point_exact(const Eigen::VectorXd& x);
  // Low-level form for deserialization: indices must be valid.
  void add_preference_indices(Preference p);

  // Keeps the first `points` points and `preferences` preferences (undo).
  void truncate(int points, int preferences);

 private:
  int dims_;
  double merge_distance_;
  Eigen::MatrixXd points_;
  std::vector<Preference> preferences_;
};

}  // namespace sps
