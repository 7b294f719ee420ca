// Simulated users answering plane (or line) queries with a synthetic goodness function.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sps/plane.hpp"
#include "testing/test_functions.hpp"

namespace sps {

struct UserAnswer {
  Eigen::VectorXd chosen;  // inside [0,1]^n
  // Extra comparisons the user made on the way, {preferred, rejected...} per zoom level
  // (empty for the argmax user).
  std::vector<std::vector<Eigen::VectorXd>> comparisons;
};

// Dense search as in the paper's experiment: a resolution x resolution lattice over the whole
// plane (s, t in [-1, 1]), or `resolution` points on the segment c -> c + u for a line.
// Points outside the box are clamped first, as the grid would show them.
UserAnswer argmax_user(const TestFunction& g, const Plane& plane, int resolution = 640);

// What a real user can do: greedy clicks on an n x n zoomable grid over `levels` levels
// (a line gets n*n points per level on the segment, halving the range each level).
UserAnswer zoom_user(const TestFunction& g, const Plane& plane, int n = 3, int levels = 4);

}  // namespace sps
