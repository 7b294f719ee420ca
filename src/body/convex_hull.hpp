// 2-D convex hull (Andrew's monotone chain) and its perimeter: a tape measure around a slice.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace body {

// Hull vertices in counter-clockwise order, without collinear points. Fewer than 3 distinct
// input points give those points.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points);

// Perimeter of a closed polygon (0 for fewer than 2 points; twice the length for 2).
double polygon_perimeter(const std::vector<Eigen::Vector2d>& polygon);

// True if p lies inside or on the counter-clockwise convex polygon `hull`.
bool hull_contains(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p);

}  // namespace body
