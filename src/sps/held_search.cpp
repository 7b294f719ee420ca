#include "sps/held_search.hpp"

#include <algorithm>

#include "sps/plane_construction.hpp"

namespace sps {

namespace {

// Scales d down so that c +- d stays in the box.
Eigen::VectorXd fit_both_sides(const Eigen::VectorXd& c, const Eigen::VectorXd& d) {
  return std::min(fit_in_box(c, d), fit_in_box(c, -d)) * d;
}

}  // namespace

Plane held_first_plane(const SearchHold& hold, const Eigen::VectorXd& scale, double extent) {
  const Eigen::Index d = scale.size();
  Plane p;
  p.c = hold.project(Eigen::VectorXd::Constant(d, 0.5));
  const Eigen::MatrixXd projector = tangent_projector(hold.normals(p.c), d);
  const Eigen::MatrixXd dirs = most_visible_tangent_directions(projector, scale, 2);
  p.u = fit_both_sides(p.c, extent * dirs.col(0));
  p.v = dirs.cols() > 1 ? fit_both_sides(p.c, extent * dirs.col(1)) : Eigen::VectorXd::Zero(d);
  if (p.is_line()) {
    // One tangent direction left: a segment through the centre (c .. c + u for a line).
    p.c -= p.u;
    p.u *= 2.0;
    p.u_neg_scale = 0.0;
  }
  return p;
}

HeldPlane hold_plane(const SearchHold& hold, const Plane& original) {
  HeldPlane held;
  Plane& plane = held.plane;
  plane = original;
  plane.c = hold.project(original.c);
  held.normals = hold.normals(plane.c);
  const TangentSpace space(held.normals, plane.c.size());
  const auto tangent = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
    if (d.size() != plane.c.size() || d.isZero(0.0)) return d;
    return space.project(d);
  };
  // The optimizer's lengths kept, so that the grid keeps its spread.
  Eigen::VectorXd u = tangent(original.u);
  Eigen::VectorXd v = tangent(original.v);
  if (u.norm() > 1e-9) u *= original.u.norm() / u.norm();
  if (!plane.is_line() && v.norm() > 1e-9) {
    if (u.norm() > 1e-9) v -= v.dot(u) / u.squaredNorm() * u;  // keep the rhombus square
    if (v.norm() > 1e-9) v *= original.v.norm() / v.norm();
  }
  plane.u = u;
  plane.v = v;
  correct_opposite_vertex(plane);
  return held;
}

}  // namespace sps
