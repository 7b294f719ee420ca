#include "sps/plane_construction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "sps/bounded_maximizer.hpp"
#include "sps/expected_improvement.hpp"
#include "sps/parallel_for.hpp"

namespace sps {

namespace {

constexpr std::array<double, 5> kLattice{-1.0, -0.5, 0.0, 0.5, 1.0};

// The longest half-diagonal of an uncertainty plane along any coordinate (box units).
constexpr double kMaxUncertaintyAxis = 2.0;

// A random unit direction of `space` (zero if it has none): a random unit vector for the
// whole space.
Eigen::VectorXd random_direction(const TangentSpace& space, int d, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd v(d);
  for (int attempt = 0; attempt < 100; ++attempt) {
    for (int k = 0; k < d; ++k) v(k) = normal(rng);
    v = space.project(v);
    if (v.norm() >= 1e-12) return v.normalized();
  }
  return Eigen::VectorXd::Zero(d);
}

Eigen::VectorXd random_unit(int d, std::mt19937_64& rng) {
  return random_direction(TangentSpace(), d, rng);
}

// The largest beta >= 0 with x + beta * dir inside [0,1]^d (infinite for dir = 0).
double room_along(const Eigen::VectorXd& x, const Eigen::VectorXd& dir) {
  double beta = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    if (dir(k) > 0.0) beta = std::min(beta, (1.0 - x(k)) / dir(k));
    if (dir(k) < 0.0) beta = std::min(beta, -x(k) / dir(k));
  }
  return std::max(0.0, beta);
}

// Half-width of the box for v: c +- v inside [0,1]^d.
Eigen::VectorXd v_bound(const Eigen::VectorXd& c) {
  return c.cwiseMin(Eigen::VectorXd::Ones(c.size()) - c).cwiseMax(0.0);
}

// Scales v down so that c +- v stays in the box.
Eigen::VectorXd fit_symmetric(const Eigen::VectorXd& c, const Eigen::VectorXd& v) {
  const Eigen::VectorXd bound = v_bound(c);
  double beta = 1.0;
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (std::abs(v(k)) > bound(k)) beta = std::min(beta, bound(k) / std::abs(v(k)));
  }
  return beta * v;
}

}  // namespace

double fit_in_box(const Eigen::VectorXd& x, const Eigen::VectorXd& dir) {
  return std::min(1.0, room_along(x, dir));
}

Eigen::VectorXd random_orthogonal_direction(const Eigen::VectorXd& u, std::mt19937_64& rng,
                                            const TangentSpace& space) {
  const int d = static_cast<int>(u.size());
  const double uu = u.squaredNorm();
  for (int attempt = 0; attempt < 100; ++attempt) {
    Eigen::VectorXd v = random_direction(space, d, rng);
    if (uu > 0.0) v -= (v.dot(u) / uu) * u;
    if (v.norm() > 1e-6) return v.normalized();
  }
  return random_direction(space, d, rng);  // d == 1: no orthogonal direction exists
}

Plane first_plane(int dims, std::mt19937_64& rng) {
  Plane p;
  p.c = Eigen::VectorXd::Constant(dims, 0.5);
  const Eigen::VectorXd u = random_unit(dims, rng);
  const Eigen::VectorXd v = random_orthogonal_direction(u, rng);
  // The same length for both half-diagonals (a square) as large as the box allows.
  const double length = 0.5 / std::max(u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff());
  p.u = length * u;
  p.v = dims > 1 ? Eigen::VectorXd(length * v) : Eigen::VectorXd::Zero(dims);
  return p;
}

void correct_opposite_vertex(Plane& plane) {
  plane.u_neg_scale = fit_in_box(plane.c, -plane.u);
}

double plane_acquisition(const PreferenceModel& model, const Plane& plane, double best_mean) {
  double total = 0.0;
  for (double s : kLattice) {
    for (double t : kLattice) total += expected_improvement(model, plane.point(s, t), best_mean);
  }
  return total / static_cast<double>(kLattice.size() * kLattice.size());
}

PlaneEiObjective::PlaneEiObjective(const PreferenceModel& model, const Plane& base,
                                   double best_mean)
    : model_(model), base_(base), best_mean_(best_mean) {
  // Lattice points depending on v (b != 0); the others are constant in v.
  for (double s : kLattice) {
    for (double t : kLattice) {
      if (s != t) lattice_.push_back({0.5 * (s + t), 0.5 * (s - t)});
    }
  }
  xs_.resize(base.c.size(), static_cast<Eigen::Index>(lattice_.size()));
}

double PlaneEiObjective::operator()(const Eigen::VectorXd& v, Eigen::VectorXd& grad) {
  const Eigen::VectorXd& u = base_.u;
  for (std::size_t j = 0; j < lattice_.size(); ++j) {
    const double a = lattice_[j].a >= 0.0 ? lattice_[j].a : lattice_[j].a * base_.u_neg_scale;
    xs_.col(static_cast<Eigen::Index>(j)) = base_.c + a * u + lattice_[j].b * v;
  }
  const Eigen::VectorXd ei = expected_improvement_batch(model_, xs_, best_mean_, &ei_grad_);
  grad.setZero(base_.c.size());
  for (std::size_t j = 0; j < lattice_.size(); ++j) {
    grad += lattice_[j].b * ei_grad_.col(static_cast<Eigen::Index>(j));
  }
  const double inv_count = 1.0 / static_cast<double>(kLattice.size() * kLattice.size());
  double value = ei.sum() * inv_count;
  grad *= inv_count;
  // Soft orthogonality: -(u.v)^2.
  const double uv = u.dot(v);
  value -= uv * uv;
  grad -= 2.0 * uv * u;
  return value;
}

Plane sps_plane(const PreferenceModel& model, const Eigen::VectorXd& x_plus,
                const Eigen::VectorXd& x_ei, double best_mean, std::mt19937_64& rng,
                const PlaneSearchSettings& settings, const TangentSpace& space) {
  const int d = static_cast<int>(x_plus.size());
  Plane base;
  base.c = x_plus;
  // x_EI lies on the tangent plane through x+ except where the box clamped it: u is its
  // tangent part, shortened so that c + u stays inside (a factor of exactly 1 without a hold,
  // where x_EI - x+ ends at a point of the box).
  base.u = space.project(x_ei - x_plus);
  base.u *= fit_in_box(x_plus, base.u);
  if (base.u.norm() < 1e-6) {
    // EI peaks at x+ itself (the model is confident), or x_EI lies across a face of the box
    // that x+ touches: still show a useful neighbourhood.
    Eigen::VectorXd dir = 0.25 * random_direction(space, d, rng);
    if (std::max(fit_in_box(x_plus, dir), fit_in_box(x_plus, -dir)) * dir.norm() < 1e-6) {
      // With a hold, x+ on several faces at once leaves every direction of the tangent space
      // (each mixes all coordinates) blocked both ways: a held centre at the box's edge came
      // out as a single point, all nine cells the same body. Move only the coordinates with
      // room on both sides, as v does below.
      const Eigen::VectorXd free = (v_bound(x_plus).array() > 1e-9).cast<double>().matrix();
      dir = 0.25 * random_direction(space.without_coordinates(free), d, rng);
    }
    const double forward = fit_in_box(x_plus, dir);
    const double backward = fit_in_box(x_plus, -dir);
    base.u = (forward >= backward ? forward : -backward) * dir;
  }
  correct_opposite_vertex(base);
  const Eigen::VectorXd& u = base.u;
  const Eigen::VectorXd bound = v_bound(x_plus);

  // Starting points, drawn before the parallel part so the result is deterministic.
  const int restarts = std::max(1, settings.restarts);
  std::vector<Eigen::VectorXd> starts;
  std::uniform_real_distribution<double> uniform(0.2, 1.0);
  for (int r = 0; r < restarts; ++r) {
    const Eigen::VectorXd dir = random_orthogonal_direction(u, rng, space);
    starts.push_back(uniform(rng) * fit_symmetric(x_plus, 10.0 * dir));
  }

  std::vector<MaximizeResult> results(static_cast<std::size_t>(restarts));
  parallel_for(restarts, settings.threads, [&](int r) {
    PlaneEiObjective objective(model, base, best_mean);
    Eigen::VectorXd g;
    // The optimizer moves w in the box of c +- w and the plane uses its tangent part.
    const Objective fn = [&](const Eigen::VectorXd& w, Eigen::VectorXd& grad) {
      const double value = objective(space.project(w), g);
      grad = space.project(g);  // P is symmetric
      return value;
    };
    results[static_cast<std::size_t>(r)] = maximize_bounded(
        fn, starts[static_cast<std::size_t>(r)], -bound, bound, settings.max_iterations, 1e-10);
  });
  const auto best = std::max_element(
      results.begin(), results.end(),
      [](const MaximizeResult& a, const MaximizeResult& b) { return a.value < b.value; });
  Plane plane = base;
  // Make the rhombus exact: remove the residual u component, then keep c +- v in the box.
  Eigen::VectorXd v = space.project(best->x);
  if (u.squaredNorm() > 0.0) v -= (v.dot(u) / u.squaredNorm()) * u;
  v = fit_symmetric(x_plus, v);
  if (v.norm() < 1e-6 && d > 1) {
    // The optimizer collapsed v (EI flat across the plane): take a random orthogonal
    // direction among the coordinates that leave room on both sides of x+. In an exact
    // corner of the box no such direction exists and the plane degenerates to a segment.
    const Eigen::VectorXd free = (bound.array() > 1e-9).cast<double>().matrix();
    const TangentSpace roomy = space.without_coordinates(free);
    const Eigen::VectorXd u_free = roomy.project(u);
    for (int attempt = 0; attempt < 20 && v.norm() < 1e-6; ++attempt) {
      Eigen::VectorXd dir = roomy.project(random_unit(d, rng));
      if (u_free.squaredNorm() > 0.0) dir -= (dir.dot(u_free) / u_free.squaredNorm()) * u_free;
      if (dir.norm() > 1e-9) v = fit_symmetric(x_plus, 10.0 * dir.normalized());
    }
  }
  plane.v = v;
  if (settings.perceptual_scale.size() == d) {
    shape_for_person(plane, settings.perceptual_scale, settings.min_plane_length,
                     settings.keep_centre, space);
  }
  return plane;
}

namespace {

// visible_direction in a tangent space (holds), where a coordinate cannot be taken out
// without the others compensating for the held quantities, which turns the optimizer's
// direction into another one (held body benchmark, 80 trials: mean gaps about 0.5 mm larger
// at planes 10 and 15 when v was made with coordinates taken out). So `start` keeps its
// coordinates: made orthogonal to `avoid` in the perceptual metric, scaled to `wanted` and
// fitted into the box as it is; when nothing of it is left, the most visible tangent
// direction orthogonal to `avoid` with the most visible room.
Eigen::VectorXd visible_tangent_direction(const Eigen::VectorXd& c, const Eigen::VectorXd& start,
                                          const Eigen::VectorXd& avoid,
                                          const Eigen::VectorXd& scale, double wanted,
                                          const TangentSpace& space) {
  const Eigen::Index d = c.size();
  const Eigen::VectorXd s2 = scale.cwiseProduct(scale);
  const double aa = avoid.dot(s2.cwiseProduct(avoid));
  const auto orthogonal = [&](Eigen::VectorXd x) {
    if (aa > 0.0) x -= (x.dot(s2.cwiseProduct(avoid)) / aa) * avoid;
    return x;
  };
  const auto visible = [&](const Eigen::VectorXd& x) { return x.cwiseProduct(scale).norm(); };
  Eigen::VectorXd dir = orthogonal(space.project(start));
  if (visible(dir) < 1e-9) {
    const Eigen::MatrixXd dirs = most_visible_tangent_directions(space.projector(d), scale, 3);
    dir = Eigen::VectorXd::Zero(d);
    for (Eigen::Index i = 0; i < dirs.cols(); ++i) {
      const Eigen::VectorXd candidate = orthogonal(dirs.col(i));
      if (candidate.norm() < 1e-9) continue;
      const Eigen::VectorXd fitted = fit_symmetric(c, candidate.normalized());
      if (visible(fitted) > visible(dir)) dir = fitted;
    }
  }
  const double length = visible(dir);
  if (length < 1e-12) return Eigen::VectorXd::Zero(d);
  return fit_symmetric(c, (wanted / length) * dir);
}

// A direction for a plane through c that a person can see: `start` restricted to the
// coordinates with room on both sides of c, orthogonal to `avoid` in the perceptual metric,
// scaled to `wanted` (perceptual length) and fitted so that c +- it stays in the box. While the
// box keeps it short, the coordinate that limits it is dropped and the next try made; the
// visibly longest result is returned (zero if none). In a tangent space:
// visible_tangent_direction.
Eigen::VectorXd visible_direction(const Eigen::VectorXd& c, const Eigen::VectorXd& start,
                                  const Eigen::VectorXd& avoid, const Eigen::VectorXd& scale,
                                  double wanted, const TangentSpace& space) {
  if (!space.whole()) return visible_tangent_direction(c, start, avoid, scale, wanted, space);
  const Eigen::Index d = c.size();
  const Eigen::VectorXd s2 = scale.cwiseProduct(scale);
  const Eigen::VectorXd bound = v_bound(c);
  Eigen::VectorXd free = (bound.array() > 0.02).cast<double>().matrix();
  Eigen::VectorXd best = Eigen::VectorXd::Zero(d);
  double best_len = -1.0;
  for (Eigen::Index attempt = 0; attempt < d; ++attempt) {
    const Eigen::VectorXd avoid_free = avoid.cwiseProduct(free);
    const double aa = avoid_free.dot(s2.cwiseProduct(avoid_free));
    const auto orthogonal = [&](Eigen::VectorXd x) {
      if (aa > 0.0) x -= (x.dot(s2.cwiseProduct(avoid_free)) / aa) * avoid_free;
      return x;
    };
    Eigen::VectorXd dir = orthogonal(start.cwiseProduct(free));
    if (dir.cwiseProduct(scale).norm() < 1e-9 * std::max(1.0, start.cwiseProduct(scale).norm())) {
      // Nothing of `start` left: the free coordinate with the most visible room that is not
      // along `avoid`.
      double best_room = 0.0;
      for (Eigen::Index k = 0; k < d; ++k) {
        if (free(k) <= 0.0 || scale(k) * bound(k) <= best_room) continue;
        const Eigen::VectorXd candidate = orthogonal(Eigen::VectorXd::Unit(d, k));
        if (candidate.cwiseProduct(scale).norm() > 1e-6 * scale(k)) {
          best_room = scale(k) * bound(k);
          dir = candidate;
        }
      }
    }
    const double dir_len = dir.cwiseProduct(scale).norm();
    if (dir_len < 1e-12) break;
    dir *= wanted / dir_len;
    const Eigen::VectorXd fitted = fit_symmetric(c, dir);
    const double len = fitted.cwiseProduct(scale).norm();
    if (len > best_len) {
      best_len = len;
      best = fitted;
    }
    if (len >= 0.999 * wanted) break;
    Eigen::Index limiting = -1;
    double tightest = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < d; ++k) {
      if (free(k) > 0.0 && std::abs(dir(k)) > 0.0 && bound(k) / std::abs(dir(k)) < tightest) {
        tightest = bound(k) / std::abs(dir(k));
        limiting = k;
      }
    }
    if (limiting < 0) break;
    free(limiting) = 0.0;
  }
  return best;
}

}  // namespace

void shape_for_person(Plane& plane, const Eigen::VectorXd& scale, double min_length,
                      bool keep_centre, const TangentSpace& space) {
  const Eigen::Index d = plane.c.size();
  if (!keep_centre && plane.u_neg_scale < 0.5 && plane.u.norm() > 1e-9) {
    // c + u/2 +- u/2 spans c .. c + u, all inside the box (both ends are).
    plane.c = plane.c + 0.5 * plane.u;
    plane.u = 0.5 * plane.u;
    plane.u_neg_scale = 1.0;
  }
  const double u_scaled = plane.u.cwiseProduct(scale).norm();
  if (u_scaled > 1e-12 && u_scaled < min_length) {
    // Longer along the same direction, as far as the box allows on both sides of c.
    const Eigen::VectorXd longer = fit_symmetric(plane.c, (min_length / u_scaled) * plane.u);
    if (longer.cwiseProduct(scale).norm() > u_scaled) plane.u = longer;
  }
  if (plane.u.cwiseProduct(scale).norm() < 0.5 * min_length) {
    // x_EI differs from x+ only where the eye cannot tell: show the visible part of that
    // direction instead (its components weighted by how visible they are).
    const Eigen::VectorXd visible =
        visible_direction(plane.c, plane.u.cwiseProduct(scale.cwiseProduct(scale)),
                          Eigen::VectorXd::Zero(d), scale, min_length, space);
    if (visible.cwiseProduct(scale).norm() > plane.u.cwiseProduct(scale).norm()) {
      plane.u = visible;
    }
  }
  correct_opposite_vertex(plane);
  if (d < 2 || plane.v.size() != d) return;
  // v orthogonal to u in the perceptual metric (orthogonal in x is not enough: u + v can look
  // like no change at all) and at least as long as min_length and half of u.
  const double u_len = plane.u.cwiseProduct(scale).norm();
  const double v_len = plane.v.cwiseProduct(scale).norm();
  const double wanted = std::max({v_len, 0.5 * u_len, min_length});
  const Eigen::VectorXd v = visible_direction(plane.c, plane.v, plane.u, scale, wanted, space);
  if (v.norm() > 1e-6) plane.v = v;
}

Plane random_plane(const Eigen::VectorXd& x_plus, std::mt19937_64& rng) {
  Plane p;
  p.c = x_plus;
  p.u = random_unit(static_cast<int>(x_plus.size()), rng);
  p.v = x_plus.size() > 1 ? random_orthogonal_direction(p.u, rng)
                          : Eigen::VectorXd(Eigen::VectorXd::Zero(x_plus.size()));
  return p;
}

namespace {

// The smallest perceptual distance between two cells of the coarsest 3x3 grid of the plane
// with both half-diagonals scaled by `factor`, each cell clamped into the box as shown.
double closest_clamped_cells(const Plane& p, const PerceptualMetric& metric, double factor) {
  std::vector<Eigen::VectorXd> cells;
  for (int s = -1; s <= 1; ++s) {
    for (int t = -1; t <= 1; ++t) {
      const Eigen::VectorXd x = p.c + factor * (0.5 * (s + t) * p.u + 0.5 * (s - t) * p.v);
      cells.push_back(x.cwiseMax(0.0).cwiseMin(1.0));
    }
  }
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = i + 1; j < cells.size(); ++j) {
      closest = std::min(closest, metric.length(cells[i] - cells[j]));
    }
  }
  return closest;
}

}  // namespace

std::optional<Plane> uncertainty_plane(const Eigen::VectorXd& c, const Eigen::MatrixXd& covariance,
                                       const PerceptualMetric& metric, double extent,
                                       double min_length, int axes_pair) {
  const Eigen::Index d = c.size();
  if (covariance.rows() != d || covariance.cols() != d || metric.dims() != d) {
    throw std::invalid_argument("uncertainty_plane: the covariance and metric need " +
                                std::to_string(d) + " rows");
  }
  // The covariance as a person sees it: of R x, with R^T R the perceptual metric.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(metric.seen_covariance(covariance));
  const auto axis = [&](Eigen::Index i) {
    const double length =
        std::max(min_length, extent * std::sqrt(std::max(0.0, eigen.eigenvalues()(i))));
    Eigen::VectorXd a = metric.unseen(eigen.eigenvectors().col(i)) * length;
    // No further than twice across the box along any coordinate: the rest would be clamped.
    const double widest = a.cwiseAbs().maxCoeff();
    if (widest > kMaxUncertaintyAxis) a *= kMaxUncertaintyAxis / widest;
    return a;
  };
  Plane p;
  p.c = c;
  // The pair of principal axes, ranked by how uncertain the estimate is along them as seen:
  // 0 the two most uncertain, then (1st, 3rd), (2nd, 3rd), (1st, 4th), ...
  int first = 0, second = 1;
  for (int k = 0; k < axes_pair; ++k) {
    if (first + 1 < second) {
      ++first;
    } else {
      first = 0;
      ++second;
    }
  }
  if (axes_pair < 0 || (d > 1 && second >= d) || (d == 1 && axes_pair > 0)) return std::nullopt;
  p.u = axis(d - 1 - first);
  p.v = d > 1 ? axis(d - 1 - second) : Eigen::VectorXd(Eigen::VectorXd::Zero(d));
  // The plane may reach beyond the box (its cells are clamped when shown): centred on the
  // estimate, with the first grid's extremes far apart, it finds the design in mind sooner
  // than one fitted into the box (body benchmark). But near a face of the box clamped cells
  // can coincide. Then the plane is moved by whole cells, so that the estimate becomes
  // another cell of its first grid (an edge or a corner: the person can still keep it, and it
  // stays the current best), and shrunk about the estimate: the largest plane whose clamped
  // cells are at least half of min_length apart, centred on the estimate where that is
  // possible, its centre always inside the box. Moving it so that the estimate fell between
  // cells took the estimate out of the grid: a photo edit chosen near +90 on a slider showed
  // +14 as the current best after the next plane.
  const double apart = 0.5 * min_length;
  // Where none keeps them that far apart, the placement and size whose closest cells lie
  // furthest apart.
  struct Placement {
    int s = 0, t = 0;
    double factor = 1.0;
    double closest = -1.0;
  };
  constexpr std::array<std::array<int, 2>, 9> kNodes = {
      {{0, 0}, {-1, -1}, {-1, 0}, {-1, 1}, {0, -1}, {0, 1}, {1, -1}, {1, 0}, {1, 1}}};
  const Plane centred = p;
  Placement chosen, furthest;
  for (double factor = 1.0; factor > 0.05 && chosen.closest < apart; factor *= 0.85) {
    for (const auto& [s, t] : kNodes) {
      Plane moved = centred;
      // The estimate at the grid's (s, t): c + a u + b v with a = (s + t) / 2, b = (s - t) / 2.
      moved.c = centred.c - factor * (0.5 * (s + t) * p.u + 0.5 * (s - t) * p.v);
      // The centre stays in the box (a plane is centred on a design).
      if (moved.c.minCoeff() < 0.0 || moved.c.maxCoeff() > 1.0) continue;
      const double closest = closest_clamped_cells(moved, metric, factor);
      if (closest > furthest.closest + 1e-9) furthest = {s, t, factor, closest};
      if (closest >= apart) {
        chosen = {s, t, factor, closest};
        break;
      }
    }
  }
  if (chosen.closest < apart) chosen = furthest;
  // A plane whose cells come closer than its smallest side (a third of min_length: what a
  // person can tell apart) is not shown; one between that and `apart` is (the session's own
  // look-alike test widens or narrows its first grid where needed).
  if (chosen.closest < min_length / 3.0) return std::nullopt;
  p.u *= chosen.factor;
  p.v *= chosen.factor;
  p.c = c - 0.5 * (chosen.s + chosen.t) * p.u - 0.5 * (chosen.s - chosen.t) * p.v;
  p.best_s = chosen.s;
  p.best_t = chosen.t;
  return p;
}

std::optional<std::pair<double, double>> plane_coordinates(const Plane& plane,
                                                           const Eigen::VectorXd& x,
                                                           double tolerance) {
  const Eigen::Index d = plane.c.size();
  if (x.size() != d || plane.u.size() != d || !x.allFinite()) return std::nullopt;
  const bool line = plane.is_line();
  Eigen::MatrixXd axes(d, line ? 1 : 2);
  axes.col(0) = plane.u;
  if (!line) axes.col(1) = plane.v;
  const Eigen::VectorXd ab = axes.colPivHouseholderQr().solve(x - plane.c);
  if (!ab.allFinite() || (axes * ab - (x - plane.c)).norm() > tolerance) return std::nullopt;
  double a = ab(0);
  const double b = line ? 0.0 : ab(1);
  if (a < 0.0) {
    if (!(plane.u_neg_scale > 0.0)) return std::nullopt;
    a /= plane.u_neg_scale;
  }
  const double s = a + b, t = a - b;
  constexpr double kSlack = 1e-9;
  if (std::abs(s) > 1.0 + kSlack || std::abs(t) > 1.0 + kSlack) return std::nullopt;
  return std::make_pair(std::clamp(s, -1.0, 1.0), std::clamp(t, -1.0, 1.0));
}

std::optional<Plane> plane_part(const Plane& plane, double s, double t, double half) {
  if (plane.is_line() || plane.u_neg_scale != 1.0 || !(half > 0.0) || !std::isfinite(half) ||
      !std::isfinite(s) || !std::isfinite(t)) {
    return std::nullopt;
  }
  const double best_s = (plane.best_s - s) / half;
  const double best_t = (plane.best_t - t) / half;
  constexpr double kSlack = 1e-9;
  if (std::abs(best_s) > 1.0 + kSlack || std::abs(best_t) > 1.0 + kSlack) return std::nullopt;
  // point() is affine here: the part's (s', t') is the plane's (s + half s', t + half t').
  Plane part = plane;
  part.c = plane.point(s, t);
  part.u = half * plane.u;
  part.v = half * plane.v;
  part.best_s = std::clamp(best_s, -1.0, 1.0);
  part.best_t = std::clamp(best_t, -1.0, 1.0);
  return part;
}

Plane sls_line(const Eigen::VectorXd& x_plus, const Eigen::VectorXd& x_ei) {
  Plane p;
  p.c = x_plus;
  p.u = x_ei - x_plus;
  p.v = Eigen::VectorXd::Zero(x_plus.size());
  p.u_neg_scale = 0.0;  // a segment from x+ to x_EI: nothing on the far side of x+
  return p;
}

}  // namespace sps
