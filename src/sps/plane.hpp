// A search plane P(c, u, v): the rhombus with vertices c +- u and c +- v (DESIGN.md).
#pragma once

#include <Eigen/Core>

namespace sps {

struct Plane {
  Eigen::VectorXd c;  // centre: the current best point x+
  Eigen::VectorXd u;  // first half-diagonal: x_EI - x+
  Eigen::VectorXd v;  // second half-diagonal, (nearly) orthogonal to u

  int dims() const { return static_cast<int>(c.size()); }

  // Grid coordinates (s, t) in [-1, 1]^2 at the coarsest zoom level: the corners are the
  // vertices ((1,1) -> c+u, (-1,-1) -> c-u, (1,-1) -> c+v, (-1,1) -> c-v), (0,0) is c.
  // The map is affine, so straight rows of cells are straight lines in parameter space.
  Eigen::VectorXd point(double s, double t) const {
    return c + 0.5 * s * (u + v) + 0.5 * t * (u - v);
  }
};

}  // namespace sps
