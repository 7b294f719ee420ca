// Searching on a surface (issue 13, holds): when some quantities of the design are held (a
// body's height...), every point shown lies on the surface where they keep their values, so
// the optimizer builds its planes there too: the centre on the surface, x_EI sought on the
// surface's tangent plane through it, and v in that tangent space. Building the plane in the
// whole box and projecting it afterwards (the first version) showed other planes than the one
// the model had chosen: for a body's height, which is nearly all in the first (most visible)
// shape coordinate, the projection swapped most of what made u and v visible for a
// compensating change of that coordinate, and the held search fell behind the free one
// (docs/benchmarks.md, Holds). The surface itself is the caller's (a body model's
// measurements); nothing here knows about bodies.
#pragma once

#include <random>

#include <Eigen/Core>

#include "sps/plane.hpp"
#include "sps/preference_model.hpp"

namespace sps {

// The held surface as the search sees it. Both calls are const and thread-safe (the search
// runs on a worker).
class SearchHold {
 public:
  virtual ~SearchHold() = default;
  // The point of the surface nearest to x inside [0,1]^n (x itself when it is on it).
  virtual Eigen::VectorXd project(const Eigen::VectorXd& x) const = 0;
  // The gradients of the held quantities at x, one row each (the surface's normals there).
  virtual Eigen::MatrixXd normals(const Eigen::VectorXd& x) const = 0;
};

// The orthogonal projector onto the directions that keep every held quantity to first order:
// I - N^T (N N^T)^+ N (a pseudo-inverse, so dependent normals do no harm). n x n; the
// identity for no normals.
Eigen::MatrixXd tangent_projector(const Eigen::MatrixXd& normals, Eigen::Index dims);

// The k (1 or 2) most visible directions of the tangent space: the leading eigenvectors of
// P S^2 P (S = diag(scale)), each of Euclidean length 1, ordered by visibility.
Eigen::MatrixXd most_visible_tangent_directions(const Eigen::MatrixXd& projector,
                                                const Eigen::VectorXd& scale, int k);

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

struct HeldPlaneSettings {
  int ei_starts = 6;
  int ei_candidates = 0;  // 0: as maximize_expected_improvement
  int plane_restarts = 10;
  int max_iterations = 25;
  int threads = 2;
  Eigen::VectorXd perceptual_scale;  // empty or SearchOptions::perceptual_scale
  double min_plane_length = 0.0;
  bool keep_centre = false;  // the centre stays x+ (a point the user set directly)
};

// The SPS plane on the surface: x+ (already on it) as the centre, u towards the maximum of EI
// over the tangent plane through x+ (inside the box), v maximizing the plane's mean EI among
// tangent directions (soft orthogonality to u as sps_plane), then both shaped for a person as
// shape_for_person does (long enough to see, v orthogonal to u in the perceptual metric),
// without leaving the tangent space.
Plane held_sps_plane(const PreferenceModel& model, const Eigen::VectorXd& x_plus,
                     const Eigen::MatrixXd& projector, double best_mean, std::mt19937_64& rng,
                     const HeldPlaneSettings& settings);

// argmax EI over the points x+ + P (y - x+) that lie in the box (y in [0,1]^n; clamped where
// the map leaves it).
Eigen::VectorXd maximize_expected_improvement_on_tangent(const PreferenceModel& model,
                                                         double best_mean,
                                                         const Eigen::VectorXd& x_plus,
                                                         const Eigen::MatrixXd& projector,
                                                         std::mt19937_64& rng, int starts,
                                                         int candidates, int threads);

// argmax of the posterior mean over the tangent plane through `anchor` (a point of the
// surface), from the anchor and the observed points with the largest means mapped onto that
// plane (as maximize_posterior_mean does in the whole box). The anchor without data.
Eigen::VectorXd maximize_posterior_mean_on_tangent(const PreferenceModel& model,
                                                   const Eigen::VectorXd& anchor,
                                                   const Eigen::MatrixXd& projector, int starts,
                                                   int threads);

}  // namespace sps
