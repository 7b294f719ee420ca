// Slicing a triangle mesh with a horizontal plane y = h into connected cross-sections.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

// One connected piece of the slice (e.g. the torso, an arm, a leg), as points in (x, z).
struct SlicePiece {
  std::vector<Eigen::Vector2d> points;
};

// Intersects every triangle with the plane y = h; intersection points on shared edges join
// pieces, so the torso and a hanging arm come out as separate pieces.
std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces, double h);

}  // namespace body
