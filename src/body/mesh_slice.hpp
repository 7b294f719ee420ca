// Slicing a triangle mesh with a plane (horizontal y = h, or any plane) into connected
// cross-sections.
#pragma once

#include <limits>
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

// The same at many heights: result i equals slice_mesh(vertices, faces, heights[i]). Each face
// is visited once to find the heights it crosses, so k slices cost one pass over the faces plus
// the faces they cross, not k passes (the girths' 61 slices: ~10x faster).
std::vector<std::vector<SlicePiece>> slice_mesh(const Vertices& vertices, const Faces& faces,
                                                const std::vector<double>& heights);
// The parts of that: the faces (ascending) that cross each height, and the slice through the
// faces listed (those crossing h: the same pieces as slice_mesh(vertices, faces, h)).
std::vector<std::vector<Eigen::Index>> faces_crossing(const Vertices& vertices, const Faces& faces,
                                                      const std::vector<double>& heights);
std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces, double h,
                                   const std::vector<Eigen::Index>& face_ids);

// A plane in any direction, for slices across a limb: `origin` on the plane, `normal` its unit
// normal, `u` and `v` unit vectors spanning it (both perpendicular to the normal and to each
// other). Points of its slice are given as ((p - origin) . u, (p - origin) . v).
struct SlicePlane {
  Eigen::Vector3d origin, normal, u, v;
};
// The plane through `origin` perpendicular to `direction` (need not be unit; not zero), with u
// and v chosen from the world axes.
SlicePlane plane_across(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

// The connected pieces of the slice of the mesh with that plane (as slice_mesh does for y = h).
// With `radius` only faces with a corner within that distance of the origin are cut: a slice
// across a limb then leaves the torso it would also cross alone (and costs a fraction).
std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces,
                                   const SlicePlane& plane,
                                   double radius = std::numeric_limits<double>::infinity());
// The same for several planes (result i for planes[i]); planes that share a normal (the levels
// across one limb) find the faces they may cut in one pass over the faces, which makes a limb's
// several slices cost little more than one.
std::vector<std::vector<SlicePiece>> slice_mesh(
    const Vertices& vertices, const Faces& faces, const std::vector<SlicePlane>& planes,
    double radius = std::numeric_limits<double>::infinity());

}  // namespace body
