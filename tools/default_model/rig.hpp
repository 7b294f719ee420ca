// Skinning weights and the joint regressor of the template mesh.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mannequin_shape.hpp"

namespace default_model {

// Distance from p to the segment a-b (a point when a == b); `closest` (optional) gets the
// segment's point nearest p.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, Vec3* closest = nullptr);

// V x 24 weights from distances to the bones, normalised by each bone's radius:
// w_j ~ exp(-((d_j - d_min) / softness)^2), at most `max_influences` non-zero per vertex
// (0 = all), rows summing to 1.
Eigen::MatrixXd skin_weights(const std::vector<Vec3>& vertices, const Skeleton& skeleton,
                             double softness, int max_influences);

// 24 x V regressor: each joint is a convex combination of the vertices around it (maximum
// entropy weights tilted so the combination reproduces the joint exactly on the template).
// Rows are non-negative and sum to 1.
Eigen::MatrixXd joint_regressor(const std::vector<Vec3>& vertices, const Skeleton& skeleton);

// The weights of one such joint over the `candidates` (vertex ids) within `radius` of `c`, as
// (vertex, weight) pairs in `out`; returns the distance between their combination and `c` (not
// zero when c lies outside the candidates' convex hull; 1e9 when there are none).
double convex_joint_weights(const std::vector<Vec3>& vertices, const Vec3& c,
                            const std::vector<int>& candidates, double radius,
                            std::vector<std::pair<int, double>>* out);

}  // namespace default_model
