// The search on a held surface (sps/held_search.hpp): planes built on the surface, in its
// tangent space, inside the box; without a hold nothing changes, and a hold that holds nothing
// builds the free search's planes (one construction for both).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <catch2/catch.hpp>

#include "sps/expected_improvement.hpp"
#include "sps/held_search.hpp"
#include "sps/plane_construction.hpp"
#include "sps/plane_search.hpp"
#include "sps/target_estimate.hpp"
#include "test_support.hpp"
#include "testing/simulated_user.hpp"
#include "testing/test_functions.hpp"

namespace {

// A linear hold a.x = b (a "measurement" that is a weighted sum of the coordinates, the first
// weighted most, as a body's height is mostly its first shape coordinate). The projection is
// the nearest point of the plane, then clamped and corrected along the free coordinates.
class LinearHold : public sps::SearchHold {
 public:
  LinearHold(Eigen::VectorXd a, double b) : a_(std::move(a)), b_(b) {}
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    Eigen::VectorXd y = x.cwiseMax(0.0).cwiseMin(1.0);
    for (int pass = 0; pass < 50; ++pass) {
      Eigen::VectorXd free_a = a_;
      for (Eigen::Index k = 0; k < y.size(); ++k) {
        const double r = b_ - a_.dot(y);
        if ((y[k] <= 0.0 && a_[k] * r < 0.0) || (y[k] >= 1.0 && a_[k] * r > 0.0)) free_a[k] = 0.0;
      }
      if (free_a.squaredNorm() == 0.0) break;
      y = (y + (b_ - a_.dot(y)) / free_a.squaredNorm() * free_a).cwiseMax(0.0).cwiseMin(1.0);
      if (std::abs(a_.dot(y) - b_) < 1e-12) break;
    }
    return y;
  }
  Eigen::MatrixXd normals(const Eigen::VectorXd&) const override { return a_.transpose(); }
  double value(const Eigen::VectorXd& x) const { return a_.dot(x); }

 private:
  Eigen::VectorXd a_;
  double b_;
};

Eigen::VectorXd weights(int d) {
  Eigen::VectorXd a = Eigen::VectorXd::Constant(d, 0.05);
  a[0] = 1.0;
  a[d - 1] = 0.2;
  return a;
}

Eigen::VectorXd perceptual_scale(int d) {
  Eigen::VectorXd s(d);
  for (int k = 0; k < d; ++k) s[k] = 300.0 / (1.0 + 2.0 * k);  // the first far most visible
  return s;
}

// A seeded d x d covariance with correlated coordinates: A A^T for a Gaussian A, plus `ridge`
// on the diagonal so that it is well conditioned.
Eigen::MatrixXd random_covariance(int d, unsigned seed, double ridge) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(d, d);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = normal(rng);
  return a * a.transpose() + ridge * Eigen::MatrixXd::Identity(d, d);
}

// A search's options in d dimensions with its own seed, the rest the defaults.
sps::SearchOptions seeded_options(int d, std::uint64_t seed) {
  sps::SearchOptions o;
  o.dims = d;
  o.seed = seed;
  return o;
}

bool inside(const Eigen::VectorXd& x) {
  return x.minCoeff() >= -1e-9 && x.maxCoeff() <= 1.0 + 1e-9;
}

// A hold on a quantity that does not change anywhere: its normal is zero, so the tangent
// space is the whole space, but as a projector (the matrix products of a held search) rather
// than as the free search's whole space.
class NothingHeld : public sps::SearchHold {
 public:
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override { return x; }
  Eigen::MatrixXd normals(const Eigen::VectorXd& x) const override {
    return Eigen::MatrixXd::Zero(1, x.size());
  }
};

double largest_difference(const sps::Plane& a, const sps::Plane& b) {
  return std::max({(a.c - b.c).cwiseAbs().maxCoeff(), (a.u - b.u).cwiseAbs().maxCoeff(),
                   (a.v - b.v).cwiseAbs().maxCoeff(), std::abs(a.u_neg_scale - b.u_neg_scale)});
}

}  // namespace

TEST_CASE("tangent projector: keeps the held quantities, idempotent, symmetric", "[held]") {
  const int d = 6;
  Eigen::MatrixXd n(2, d);
  n.row(0) = weights(d).transpose();
  n.row(1) = Eigen::VectorXd::LinSpaced(d, -1.0, 1.0).transpose();
  const Eigen::MatrixXd p = sps::tangent_projector(n, d);
  CHECK((n * p).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((p * p - p).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((p - p.transpose()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(p.trace() == Approx(d - 2).margin(1e-9));
  // Dependent normals (the same quantity twice) leave one constraint, not a blow-up.
  Eigen::MatrixXd twice(2, d);
  twice.row(0) = weights(d).transpose();
  twice.row(1) = 2.0 * weights(d).transpose();
  CHECK(sps::tangent_projector(twice, d).trace() == Approx(d - 1).margin(1e-9));
  CHECK(sps::tangent_projector(Eigen::MatrixXd(0, d), d).isIdentity());
}

TEST_CASE("held first plane: on the surface, tangent, visible, inside the box", "[held]") {
  const int d = 8;
  const LinearHold hold(weights(d), 0.62);
  const Eigen::VectorXd scale = perceptual_scale(d);
  const sps::Plane p = sps::held_first_plane(hold, scale, sps::kVisibleFirstPlaneExtent);
  CHECK(hold.value(p.c) == Approx(0.62).margin(1e-9));
  CHECK(std::abs(weights(d).dot(p.u)) < 1e-9);
  CHECK(std::abs(weights(d).dot(p.v)) < 1e-9);
  for (double s : {-1.0, 1.0}) {
    CHECK(inside(p.c + s * p.u));
    CHECK(inside(p.c + s * p.v));
  }
  // Not degenerate: u is the most visible tangent direction per unit of change (more than
  // what the hold leaves of the first coordinate, which the plane without hold spans), and v
  // another one, orthogonal to it.
  const Eigen::MatrixXd tangent = sps::tangent_projector(weights(d).transpose(), d);
  const auto per_unit = [&](const Eigen::VectorXd& w) {
    return w.cwiseProduct(scale).norm() / w.norm();
  };
  REQUIRE(p.u.norm() > 0.1);
  REQUIRE(p.v.norm() > 0.1);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    Eigen::VectorXd w(d);
    for (int k = 0; k < d; ++k) w[k] = normal(rng);
    CHECK(per_unit(p.u) >= per_unit(tangent * w) - 1e-9);
  }
  const sps::Plane free = sps::visible_first_plane(scale);
  CHECK(per_unit(p.u) >= per_unit(tangent * free.u) - 1e-9);
  CHECK(per_unit(p.v) > 0.3 * per_unit(p.u));
  CHECK(std::abs(p.u.dot(p.v)) < 1e-9);
}

TEST_CASE("a held search builds every plane on the surface, in its tangent space",
          "[held][search]") {
  const int d = 6;
  auto hold = std::make_shared<const LinearHold>(weights(d), 0.55);
  sps::SearchOptions o = seeded_options(d, 11);
  sps::PlaneSearch search(o);
  search.set_perceptual_scale(perceptual_scale(d));
  const sps::Plane unheld = search.current_plane();
  search.set_hold(hold);
  REQUIRE(search.hold() == hold.get());
  CHECK(search.current_plane().c == unheld.c);  // installing a hold keeps the plane shown
  // Before any choice the first plane is chosen again, on the surface.
  REQUIRE(search.use_visible_first_plane());
  CHECK(hold->value(search.current_plane().c) == Approx(0.55).margin(1e-9));
  const auto f = sps::make_test_function("gaussian", d);
  for (int i = 0; i < 6; ++i) {
    const sps::Plane& p = search.current_plane();
    INFO("plane " << i);
    CHECK(hold->value(p.c) == Approx(0.55).margin(1e-6));
    CHECK(std::abs(weights(d).dot(p.u)) < 1e-6);
    CHECK(std::abs(weights(d).dot(p.v)) < 1e-6);
    CHECK(inside(p.c));
    CHECK(inside(p.c + p.u));
    CHECK(inside(p.c - p.u_neg_scale * p.u));
    CHECK(inside(p.c + p.v));
    CHECK(inside(p.c - p.v));
    CHECK(p.u.norm() > 1e-3);
    CHECK(p.v.norm() > 1e-3);
    if (i > 0) {
      // Shaped for a person: v orthogonal to u in the perceptual metric.
      const Eigen::VectorXd s = perceptual_scale(d);
      CHECK(std::abs(p.u.cwiseProduct(s).dot(p.v.cwiseProduct(s))) <
            1e-9 * p.u.cwiseProduct(s).norm() * p.v.cwiseProduct(s).norm());
    }
    // The user picks on the plane as shown: every point on the surface.
    const auto answer = sps::zoom_user(*f, p);
    search.submit(hold->project(answer.chosen));
  }
  // Released: the next planes are the search's own again (the data stay).
  const int points = search.data().point_count();
  search.set_hold(nullptr);
  CHECK(search.hold() == nullptr);
  CHECK(search.data().point_count() == points);
}

TEST_CASE("without a hold the search is unchanged by the hold code", "[held][search]") {
  const int d = 5;
  sps::SearchOptions o = seeded_options(d, 3);
  sps::PlaneSearch a(o);
  sps::PlaneSearch b(o);
  a.set_perceptual_scale(perceptual_scale(d));
  b.set_perceptual_scale(perceptual_scale(d));
  a.use_visible_first_plane();
  b.use_visible_first_plane();
  b.set_hold(nullptr);  // installing and releasing "no hold" changes nothing
  const auto f = sps::make_test_function("gaussian", d);
  for (int i = 0; i < 4; ++i) {
    const sps::Plane& pa = a.current_plane();
    const sps::Plane& pb = b.current_plane();
    REQUIRE(pa.c == pb.c);
    REQUIRE(pa.u == pb.u);
    REQUIRE(pa.v == pb.v);
    const auto answer = sps::zoom_user(*f, pa);
    a.submit(answer.chosen, answer.comparisons);
    b.submit(answer.chosen, answer.comparisons);
  }
}

TEST_CASE("tangent space: the whole space is exact, a held one keeps its quantities", "[held]") {
  const int d = 5;
  std::mt19937_64 rng(4);
  const Eigen::VectorXd x = sps_test::random_point(d, rng, -1.0, 1.0);
  const sps::TangentSpace whole;
  CHECK(whole.whole());
  CHECK((whole.project(x) - x).cwiseAbs().maxCoeff() == 0.0);
  Eigen::VectorXd keep = Eigen::VectorXd::Ones(d);
  keep[1] = 0.0;
  const Eigen::VectorXd masked = whole.without_coordinates(keep).project(x);
  CHECK(masked[1] == 0.0);
  CHECK((masked - x).cwiseAbs().sum() == Approx(std::abs(x[1])).margin(1e-15));

  const sps::TangentSpace held(weights(d).transpose(), d);
  REQUIRE_FALSE(held.whole());
  CHECK(std::abs(weights(d).dot(held.project(x))) < 1e-12);
  const Eigen::VectorXd origin = Eigen::VectorXd::Constant(d, 0.4);
  CHECK(std::abs(weights(d).dot(held.through(origin, x) - origin)) < 1e-12);
  // Without coordinate 1: still tangent, coordinate 1 unchanged, and the largest such part of x
  // (what is left is orthogonal to every allowed direction).
  const sps::TangentSpace narrower = held.without_coordinates(keep);
  const Eigen::VectorXd p = narrower.project(x);
  CHECK(std::abs(weights(d).dot(p)) < 1e-12);
  CHECK(std::abs(p[1]) < 1e-12);
  CHECK((narrower.project(p) - p).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(p.norm() > 0.1);
  // Nothing held as a projector: the identity, as the whole space.
  const sps::TangentSpace nothing(Eigen::MatrixXd::Zero(1, d), d);
  REQUIRE_FALSE(nothing.whole());
  CHECK((nothing.project(x) - x).cwiseAbs().maxCoeff() < 1e-15);
}

TEST_CASE("one plane construction: holding nothing builds the free plane", "[held][plane]") {
  // The held path (EI on the tangent plane, u its tangent part, v among tangent directions)
  // with a tangent space that is everything must give the free plane: if the two ever became
  // separate constructions again they would differ here. (Shaped for a person, a tangent
  // space keeps every coordinate of v, so there the two differ by design.)
  for (const int d : {3, 6}) {
    INFO("d " << d);
    std::mt19937_64 data_rng(30 + static_cast<unsigned>(d));
    const sps::PreferenceData data = sps_test::random_data(d, 6, data_rng);
    const sps::ModelSettings model_settings;
    const auto model =
        sps::PreferenceModel::fit(data, model_settings, sps::PreferenceModel(d, model_settings));
    const Eigen::VectorXd x_plus = model.points().col(model.best_observed_index());
    const double best_mean = model.mean(x_plus);
    const sps::TangentSpace nothing(Eigen::MatrixXd::Zero(1, d), d);
    REQUIRE_FALSE(nothing.whole());
    std::mt19937_64 free_rng(8);
    std::mt19937_64 held_rng(8);
    const Eigen::VectorXd free_ei =
        sps::maximize_expected_improvement(model, best_mean, x_plus, free_rng, {});
    const Eigen::VectorXd held_ei =
        sps::maximize_expected_improvement(model, best_mean, x_plus, held_rng, {}, nothing);
    CHECK((free_ei - held_ei).cwiseAbs().maxCoeff() < 1e-9);
    const sps::Plane free = sps::sps_plane(model, x_plus, free_ei, best_mean, free_rng, {});
    const sps::Plane held =
        sps::sps_plane(model, x_plus, held_ei, best_mean, held_rng, {}, nothing);
    REQUIRE(free.u.norm() > 1e-3);
    REQUIRE(free.v.norm() > 1e-3);
    CHECK(largest_difference(free, held) < 1e-9);
  }
}

TEST_CASE("the estimate given the holds stays in the box", "[held][target]") {
  // A hold set far from the choices: the Gaussian's move along correlated coordinates leaves
  // the box; those coordinates are held at the faces they cross and the rest conditioned.
  const int d = 5;
  Eigen::MatrixXd c = Eigen::MatrixXd::Identity(d, d);
  c(0, 1) = c(1, 0) = 0.9;  // the second coordinate follows the first closely
  c(0, 2) = c(2, 0) = -0.8;
  const LinearHold hold(weights(d), 0.95);
  Eigen::VectorXd t(d);
  t << 0.2, 0.9, 0.1, 0.5, 0.5;
  const Eigen::VectorXd n = weights(d);
  const Eigen::VectorXd unbounded = t + c * n * ((0.95 - n.dot(t)) / n.dot(c * n));
  REQUIRE_FALSE(inside(unbounded));
  const Eigen::VectorXd given = sps::estimate_given_holds(t, hold.project(t), c, n.transpose());
  CHECK(inside(given));
  CHECK(hold.value(given) == Approx(0.95).margin(1e-9));
  CHECK(given(1) == Approx(1.0).margin(1e-12));  // pushed to the face it crossed
  CHECK(given(2) == Approx(0.0).margin(1e-12));
}

TEST_CASE("a held plane centred on several faces of the box still spans a neighbourhood",
          "[held][plane]") {
  // Every tangent direction of a hold mixes all coordinates, so at a centre on three faces
  // nearly every one leaves the box both ways; the plane came out as a single point (nine
  // identical cells, and the choice among them taught nothing).
  const int d = 6;
  std::mt19937_64 data_rng(41);
  const sps::PreferenceData data = sps_test::random_data(d, 6, data_rng);
  const sps::ModelSettings model_settings;
  const auto model =
      sps::PreferenceModel::fit(data, model_settings, sps::PreferenceModel(d, model_settings));
  Eigen::VectorXd x_plus(d);
  x_plus << 0.6, 0.0, 1.0, 0.4, 0.0, 0.5;
  const sps::TangentSpace tangent(weights(d).transpose(), d);
  for (unsigned seed = 0; seed < 8; ++seed) {
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    // EI peaks at the centre itself: the fallback direction is the one under test.
    const sps::Plane plane =
        sps::sps_plane(model, x_plus, x_plus, model.mean(x_plus), rng, {}, tangent);
    CHECK(plane.u.norm() > 1e-3);
    CHECK(plane.v.norm() > 1e-3);
    CHECK(std::abs(weights(d).dot(plane.u)) < 1e-9);
    CHECK(std::abs(weights(d).dot(plane.v)) < 1e-9);
    CHECK(inside(plane.c + plane.u));
    CHECK(inside(plane.c - plane.u_neg_scale * plane.u));
    CHECK(inside(plane.c + plane.v));
    CHECK(inside(plane.c - plane.v));
  }
}

TEST_CASE("a search holding nothing makes the free search's planes", "[held][search]") {
  for (const auto method : {sps::Method::kSps, sps::Method::kSls}) {
    INFO(sps::method_name(method));
    const int d = 5;
    sps::SearchOptions o = seeded_options(d, 9);
    o.method = method;
    sps::PlaneSearch free(o);
    sps::PlaneSearch held(o);
    held.set_hold(std::make_shared<const NothingHeld>());  // the first plane stays as it was
    const auto f = sps::make_test_function("gaussian", d);
    for (int i = 0; i < 5; ++i) {
      INFO("plane " << i);
      REQUIRE(largest_difference(free.current_plane(), held.current_plane()) < 1e-9);
      const auto answer = sps::zoom_user(*f, free.current_plane());
      free.submit(answer.chosen, answer.comparisons);
      held.submit(answer.chosen, answer.comparisons);
    }
    CHECK(largest_difference(free.current_plane(), held.current_plane()) < 1e-9);
  }
}

TEST_CASE("a plane moved onto a hold: centre on it, directions tangent, lengths kept", "[held]") {
  const int d = 6;
  const LinearHold hold(weights(d), 0.5);
  sps::Plane plane;
  plane.c = Eigen::VectorXd::Constant(d, 0.45);
  plane.u = Eigen::VectorXd::Zero(d);
  plane.u[0] = 0.2;
  plane.u[2] = 0.1;
  plane.v = Eigen::VectorXd::Zero(d);
  plane.v[1] = 0.15;
  plane.v[0] = 0.05;
  const sps::HeldPlane held = sps::hold_plane(hold, plane);
  CHECK(hold.value(held.plane.c) == Approx(0.5).margin(1e-9));
  CHECK(std::abs(weights(d).dot(held.plane.u)) < 1e-9);
  CHECK(std::abs(weights(d).dot(held.plane.v)) < 1e-9);
  CHECK(held.plane.u.norm() == Approx(plane.u.norm()).epsilon(1e-12));
  CHECK(held.plane.v.norm() == Approx(plane.v.norm()).epsilon(1e-12));
  CHECK(std::abs(held.plane.u.dot(held.plane.v)) < 1e-12);
  CHECK(inside(held.plane.c - held.plane.u_neg_scale * held.plane.u));
  REQUIRE(held.normals.rows() == 1);
  CHECK((held.normals.row(0).transpose() - weights(d)).cwiseAbs().maxCoeff() < 1e-12);
  // A cell of the plane projected with the centre's normals lands on the surface.
  const Eigen::VectorXd cell = hold.project_near(held.plane.point(0.5, -0.5), held.normals);
  CHECK(hold.value(cell) == Approx(0.5).margin(1e-9));
}

TEST_CASE("the estimate's uncertainty given the holds: none along them, the rest kept",
          "[held][target]") {
  const Eigen::MatrixXd c = random_covariance(4, 5, 0.1);
  const Eigen::RowVectorXd n = weights(4).transpose();
  const Eigen::MatrixXd given = sps::covariance_given_holds(c, n);
  // Known exactly along the held quantity, symmetric, never more uncertain than before.
  CHECK((n * given).norm() < 1e-9 * c.norm());
  CHECK((given - given.transpose()).norm() < 1e-12 * c.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> less(c - given);
  CHECK(less.eigenvalues().minCoeff() > -1e-9 * c.norm());
  // The limit of ever more information along the normal: (C^-1 + lambda n^T n)^-1.
  const Eigen::MatrixXd information = c.inverse() + 1e9 * n.transpose() * n;
  CHECK((information.inverse() - given).norm() < 1e-6 * c.norm());
  // Nothing held: unchanged; a normal given twice: the same as once; a vanishing normal
  // (a quantity that does not change here) says nothing.
  CHECK((sps::covariance_given_holds(c, Eigen::MatrixXd(0, 4)) - c).norm() == 0.0);
  Eigen::MatrixXd twice(2, 4);
  twice << n, n;
  CHECK((sps::covariance_given_holds(c, twice) - given).norm() < 1e-9 * c.norm());
  CHECK((sps::covariance_given_holds(c, Eigen::MatrixXd::Zero(1, 4)) - c).norm() <
        1e-12 * c.norm());
  CHECK_THROWS_AS(sps::covariance_given_holds(c, Eigen::MatrixXd::Ones(1, 3)),
                  std::invalid_argument);
}

TEST_CASE("the estimate given the holds: the posterior's mean on the held surface",
          "[held][target]") {
  const Eigen::MatrixXd c = random_covariance(5, 8, 0.2);
  const LinearHold hold(weights(5), 0.55);
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(5, 0.35, 0.6);
  const Eigen::VectorXd nearest = hold.project(t);
  const Eigen::VectorXd n = weights(5);
  const Eigen::VectorXd given = sps::estimate_given_holds(t, nearest, c, n.transpose());
  // On the surface, and the Gaussian's conditional mean there, exactly for a linear hold.
  CHECK(hold.value(given) == Approx(0.55).margin(1e-12));
  const Eigen::VectorXd exact = t + c * n * ((0.55 - n.dot(t)) / n.dot(c * n));
  CHECK((given - exact).norm() < 1e-12);
  // Closer to t than the nearest point in the posterior's own measure (the Mahalanobis
  // distance), which is what the move is for; an isotropic posterior moves to the nearest.
  const Eigen::MatrixXd precision = c.inverse();
  const auto mahalanobis = [&](const Eigen::VectorXd& x) {
    return (x - t).dot(precision * (x - t));
  };
  CHECK(mahalanobis(given) < mahalanobis(nearest));
  CHECK((sps::estimate_given_holds(t, nearest, Eigen::MatrixXd::Identity(5, 5), n.transpose()) -
         nearest)
            .norm() < 1e-12);
  CHECK((sps::estimate_given_holds(t, nearest, c, Eigen::MatrixXd(0, 5)) - nearest).norm() == 0.0);
  CHECK_THROWS_AS(sps::estimate_given_holds(t, nearest.head(4), c, n.transpose()),
                  std::invalid_argument);
}

TEST_CASE("a held search with a population spans its planes along the uncertainty left",
          "[held][search][target]") {
  const int d = 5;
  auto hold = std::make_shared<const LinearHold>(weights(d), 0.55);
  sps::SearchOptions o = seeded_options(d, 3);
  o.threads = 1;
  o.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  sps::PlaneSearch search(o);
  const Eigen::VectorXd scale = perceptual_scale(d);
  search.set_perceptual_scale(scale);
  sps::Population population;
  population.mean = Eigen::VectorXd::Constant(d, 0.5);
  population.sd = Eigen::VectorXd::Constant(d, 1.0 / 6.0);
  search.set_population(population);
  search.set_hold(hold);
  REQUIRE(search.use_visible_first_plane());  // the first plane chosen again, on the surface
  const sps::TargetModel model{sps::PerceptualMetric(scale), population,
                               search.options().choice_temperature_mm,
                               search.options().choice_region_slack};
  const Eigen::VectorXd goal = hold->project(Eigen::VectorXd::LinSpaced(d, 0.3, 0.7));
  for (int i = 0; i < 4; ++i) {
    const sps::Plane& p = search.current_plane();
    INFO("plane " << i);
    CHECK(hold->value(p.c) == Approx(0.55).margin(1e-6));
    // In the surface's tangent space, as every held plane is.
    CHECK(std::abs(weights(d).dot(p.u)) < 1e-6 * p.u.norm());
    CHECK(std::abs(weights(d).dot(p.v)) < 1e-6 * p.v.norm());
    if (i > 0) {
      // Along the most uncertain direction left once the held value is known (the paper's
      // plane, towards the expected improvement, would point elsewhere).
      const Eigen::MatrixXd given = sps::covariance_given_holds(
          sps::target_posterior_covariance(search.data(), model, p.c), weights(d).transpose());
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
          model.metric.seen_covariance(given));
      const Eigen::VectorXd most = model.metric.unseen(eigen.eigenvectors().col(d - 1));
      CHECK(std::abs(most.normalized().dot(p.u.normalized())) > 0.98);
    }
    Eigen::VectorXd best = p.c;
    for (double s = -1.0; s <= 1.0; s += 0.25) {
      for (double t = -1.0; t <= 1.0; t += 0.25) {
        const Eigen::VectorXd x = hold->project(p.point(s, t));
        if ((x - goal).cwiseProduct(scale).norm() < (best - goal).cwiseProduct(scale).norm()) {
          best = x;
        }
      }
    }
    search.submit(best);
  }
}
