// Searching on a surface (holds): when some quantities of the design are held (a body's
// height...), every point shown lies on the surface where they keep their values, so the
// optimizer builds its planes there too: the centre on the surface, x_EI sought on the
// surface's tangent plane through it, and u and v in that tangent space. This is the free
// search's own construction (plane_construction.hpp) run in that tangent space
// (tangent_space.hpp). Building the plane in the whole box and projecting it afterwards (the
// first version) showed other planes than the one the model had chosen: for a body's height,
// which is nearly all in the first (most visible) shape coordinate, the projection swapped
// most of what made u and v visible for a compensating change of that coordinate, and the
// held search fell behind the free one (docs/benchmarks.md, Holds). With an estimate of the
// design in mind, the centre is that estimate moved onto the surface as the choices allow
// (target_estimate.hpp, estimate_given_holds) and uncertainty planes
// (PlaneAxes::kTargetUncertainty) are spanned along its uncertainty given the held values
// (covariance_given_holds), whose axes lie in that tangent space: the nearest surface point
// and the paper's construction there had left the held search behind the free one from
// plane 2 (40 people, seeds 2000-2039, mean gap at plane 15 6.94 mm; 5.91 with the planes,
// 5.07 with both, free 5.39). The surface itself is the caller's (a body model's
// measurements); nothing here knows about bodies.
#pragma once

#include <Eigen/Core>

#include "sps/plane.hpp"
#include "sps/tangent_space.hpp"

namespace sps {

// The held surface: what the optimizer builds its planes on and what every point shown is
// projected onto. Every call is const and thread-safe (the search runs on a worker, cells are
// projected on two threads).
class SearchHold {
 public:
  virtual ~SearchHold() = default;
  // The point of the surface nearest to x inside [0,1]^n (x itself when it is on it).
  virtual Eigen::VectorXd project(const Eigen::VectorXd& x) const = 0;
  // The gradients of the held quantities at x, one row each (the surface's normals there).
  virtual Eigen::MatrixXd normals(const Eigen::VectorXd& x) const = 0;
  // project(x) for a point near a point of the surface whose normals are `nearby_normals`
  // (the cells of a plane and its centre): a surface may reuse them instead of computing new
  // ones, which is much cheaper for the many cells of one plane.
  virtual Eigen::VectorXd project_near(const Eigen::VectorXd& x,
                                       const Eigen::MatrixXd& /*nearby_normals*/) const {
    return project(x);
  }
};

// The half-diagonal (Euclidean, in [0, 1] units) of the first plane with a hold: wider than
// without one (kVisibleFirstPlaneExtent, 0.4), because the hold takes away the most visible
// direction and the first plane spans less visible ones. Held body benchmark, 2 x 20 trials
// (docs/benchmarks.md, Holds): mean gap at plane 15 8.9 mm with 0.5 against 9.6 with 0.4;
// 0.6 was worse (11.4 on the first 20).
constexpr double kHeldFirstPlaneExtent = 0.5;

// The first plane with a hold and a perceptual scale: centred on the surface point nearest
// to the box's centre, spanning the two most visible tangent directions, each
// `extent` long (Euclidean, as visible_first_plane) or less where the box ends.
Plane held_first_plane(const SearchHold& hold, const Eigen::VectorXd& scale, double extent);

// A plane as shown with a hold: its centre moved onto the surface and u and v into the
// tangent space there (their lengths kept, v orthogonal to u, the opposite-vertex correction
// made again), with the surface's normals at the centre for projecting its cells
// (SearchHold::project_near). A plane the optimizer built on the surface changes only within
// the projection's tolerance; one made before the hold was installed (the plane on screen
// then, or one read from a session file) is moved onto it.
struct HeldPlane {
  Plane plane;
  Eigen::MatrixXd normals;  // hold.normals(plane.c)
};
HeldPlane hold_plane(const SearchHold& hold, const Plane& plane);

}  // namespace sps
