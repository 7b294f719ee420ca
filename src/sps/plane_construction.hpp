// Building the next search plane (paper, "Plane Construction"): c = x+, u = x_EI - x+, v by
// maximizing the mean EI over a 5x5 lattice on the plane with a soft orthogonality term, plus
// the baselines (random planes, sequential line search) and the first plane. With holds the
// same construction runs in the tangent space of the held surface at x+ (sps/held_search.hpp):
// a free search is the held one in the whole space.
#pragma once

#include <optional>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sps/perceptual_metric.hpp"
#include "sps/plane.hpp"
#include "sps/preference_model.hpp"
#include "sps/tangent_space.hpp"

namespace sps {

// Largest beta in [0, 1] with x + beta * dir inside [0,1]^d.
double fit_in_box(const Eigen::VectorXd& x, const Eigen::VectorXd& dir);

// A random unit vector of `space` orthogonal to `u` (any unit vector of it if u is zero).
Eigen::VectorXd random_orthogonal_direction(const Eigen::VectorXd& u, std::mt19937_64& rng,
                                            const TangentSpace& space = {});

// First plane (no data): the largest square with a random orientation centred at 0.5 that
// fits in the box.
Plane first_plane(int dims, std::mt19937_64& rng);

// Sets u_neg_scale so that c - u_neg_scale * u stays in the box (the opposite-vertex
// correction), and guards against a degenerate u.
void correct_opposite_vertex(Plane& plane);

// The plane acquisition: mean EI over the 5x5 lattice (s, t in {-1,-.5,0,.5,1}).
double plane_acquisition(const PreferenceModel& model, const Plane& plane, double best_mean);

// The objective of the search for v given c and u (sps_plane, and the held search on a
// tangent plane): the plane's mean EI over the 5x5 lattice minus the soft-orthogonality
// penalty (u.v)^2, with its gradient in v. Holds scratch matrices: one object per thread.
class PlaneEiObjective {
 public:
  PlaneEiObjective(const PreferenceModel& model, const Plane& base, double best_mean);
  double operator()(const Eigen::VectorXd& v, Eigen::VectorXd& grad);

 private:
  struct LatticePoint {
    double a, b;  // the point c + a u + b v (a < 0 scaled by the plane's u_neg_scale)
  };
  const PreferenceModel& model_;
  const Plane& base_;
  double best_mean_;
  std::vector<LatticePoint> lattice_;  // only the points that depend on v (b != 0)
  Eigen::MatrixXd xs_, ei_grad_;
};

struct PlaneSearchSettings {
  int restarts = 10;
  int max_iterations = 25;
  int threads = 2;
  Eigen::VectorXd perceptual_scale;  // empty, or SearchOptions::perceptual_scale
  double min_plane_length = 0.0;     // SearchOptions::min_plane_length
  bool keep_centre = false;          // c stays x+ (a point the user set directly)
};

// The person-friendly plane shape used with a perceptual scale (see SearchOptions): when c
// sits close to a bound along -u (u_neg_scale < 1/2) the plane is moved forward so that c
// becomes its corner c' - u' (no fold of look-alike cells behind it); u is lengthened to
// `min_length` in `scale` units where the box allows, or replaced by the visible part of its
// direction when it is invisible; v is made orthogonal to u in the perceptual metric and as
// long as min_length and half of u, within the coordinates that leave room (in a tangent
// space, with every coordinate: fitted into the box as it is).
// With keep_centre the plane is never moved forward (c stays where it is). Every direction
// taken is one of `space` (u and v in it stay in it).
void shape_for_person(Plane& plane, const Eigen::VectorXd& scale, double min_length,
                      bool keep_centre = false, const TangentSpace& space = {});

// The SPS plane through x+ (c = x+ when no perceptual scale moves it), u towards x_EI and v
// maximizing the plane's mean EI, all within `space` (the tangent space of the held surface at
// x+; x_EI a point of the tangent plane there, as maximize_expected_improvement finds it in
// that space).
Plane sps_plane(const PreferenceModel& model, const Eigen::VectorXd& x_plus,
                const Eigen::VectorXd& x_ei, double best_mean, std::mt19937_64& rng,
                const PlaneSearchSettings& settings, const TangentSpace& space = {});

// c = x+, random orthogonal u, v of length 1 (points outside the box are clamped when shown).
Plane random_plane(const Eigen::VectorXd& x_plus, std::mt19937_64& rng);

// The plane through c along the directions in which the estimate of the design in mind is
// least certain as a person sees them: the principal axes of `covariance` (box units) in
// `metric`, each half-diagonal `extent` standard deviations long and at
// least `min_length` (perceptual units). Like random planes it may reach beyond the box (its
// cells are clamped when shown), shrunk until the cells of its first 3x3 grid, clamped, are
// half of min_length apart where it can be; none where even the best shrink leaves two cells
// closer than a third of min_length (the caller builds another kind of plane).
// `axes_pair` 0 takes the two most uncertain axes; 1, 2, 3, ... the next pairs in the order
// (1st, 3rd), (2nd, 3rd), (1st, 4th), (2nd, 4th), ...; none beyond the last pair.
std::optional<Plane> uncertainty_plane(const Eigen::VectorXd& c, const Eigen::MatrixXd& covariance,
                                       const PerceptualMetric& metric, double extent,
                                       double min_length, int axes_pair = 0);

// The grid coordinates (s, t) of x on the plane (Plane::point(s, t) == x within `tolerance`
// in box units, inside [-1, 1]^2), or nullopt where x is not on the plane's square.
std::optional<std::pair<double, double>> plane_coordinates(const Plane& plane,
                                                           const Eigen::VectorXd& x,
                                                           double tolerance = 1e-9);

// The part of `plane` around its grid coordinates (s, t), `half` wide in each, as a plane of
// its own: its square is that part, so its first grid is the grid `plane` shows there, and
// the current best keeps its place (best_s, best_t in the part's coordinates; it must lie in
// the part). nullopt for a line, a plane with the opposite-vertex correction (not affine), a
// non-positive or non-finite `half`, or a part without the current best.
std::optional<Plane> plane_part(const Plane& plane, double s, double t, double half);

// Sequential line search: the segment x+ -> x_EI, as a plane with v = 0.
Plane sls_line(const Eigen::VectorXd& x_plus, const Eigen::VectorXd& x_ei);

}  // namespace sps
