#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "sps/expected_improvement.hpp"
#include "sps/plane_construction.hpp"
#include "test_support.hpp"

using sps_test::numeric_gradient;
using sps_test::random_point;

namespace {

sps::PreferenceModel fitted_model(int d, int preferences, unsigned seed) {
  std::mt19937_64 rng(seed);
  const sps::PreferenceData data = sps_test::random_data(d, preferences, rng);
  const sps::ModelSettings settings;
  return sps::PreferenceModel::fit(data, settings, sps::PreferenceModel(d, settings));
}

// What the plane construction starts from: x+, its posterior mean and x_EI.
struct Incumbent {
  Eigen::VectorXd x_plus;
  double best_mean = 0.0;
  Eigen::VectorXd x_ei;
};

Incumbent incumbent(const sps::PreferenceModel& model, std::mt19937_64& rng) {
  Incumbent in;
  in.x_plus = model.points().col(model.best_observed_index());
  in.best_mean = model.mean(in.x_plus);
  in.x_ei = sps::maximize_expected_improvement(model, in.best_mean, in.x_plus, rng,
                                               sps::EiSearchSettings{});
  return in;
}

// E[max(y - best, 0)] for y ~ N(mean, var) by the trapezoid rule over +-12 sigma.
double integrated_ei(double mean, double var, double best) {
  const double sigma = std::sqrt(var);
  const int steps = 200000;
  const double lo = mean - 12.0 * sigma;
  const double hi = mean + 12.0 * sigma;
  const double h = (hi - lo) / steps;
  double sum = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double y = lo + h * i;
    const double density =
        std::exp(-0.5 * (y - mean) * (y - mean) / var) / (sigma * std::sqrt(2.0 * M_PI));
    const double w = (i == 0 || i == steps) ? 0.5 : 1.0;
    sum += w * std::max(y - best, 0.0) * density;
  }
  return sum * h;
}

}  // namespace

TEST_CASE("expected improvement equals a direct numerical integration", "[ei]") {
  const int d = 3;
  const auto model = fitted_model(d, 4, 21);
  std::mt19937_64 rng(4);
  const int best = model.best_observed_index();
  const double best_mean = model.mean(model.points().col(best));
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::VectorXd x = random_point(d, rng);
    const double ei = sps::expected_improvement(model, x, best_mean);
    const double reference = integrated_ei(model.mean(x), model.variance(x), best_mean);
    CHECK(ei == Approx(reference).epsilon(1e-6).margin(1e-12));
    CHECK(ei >= 0.0);
  }
}

TEST_CASE("expected improvement gradient matches finite differences", "[ei][gradient]") {
  const int d = 5;
  const auto model = fitted_model(d, 6, 22);
  std::mt19937_64 rng(8);
  const double best_mean = model.mean(model.points().col(model.best_observed_index()));
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::VectorXd x = random_point(d, rng);
    Eigen::VectorXd grad;
    sps::expected_improvement(model, x, best_mean, &grad);
    const auto fn = [&](const Eigen::VectorXd& z) {
      return sps::expected_improvement(model, z, best_mean);
    };
    CHECK((grad - numeric_gradient(fn, x, 1e-6)).norm() < 1e-6 * (1.0 + grad.norm()));
  }
}

TEST_CASE("x_EI beats every random point and stays in the box", "[ei]") {
  const int d = 4;
  const auto model = fitted_model(d, 5, 23);
  std::mt19937_64 rng(1);
  const auto [x_plus, best_mean, x_ei] = incumbent(model, rng);
  REQUIRE(x_ei.size() == d);
  CHECK(x_ei.minCoeff() >= 0.0);
  CHECK(x_ei.maxCoeff() <= 1.0);
  const double best = sps::expected_improvement(model, x_ei, best_mean);
  std::mt19937_64 probe(99);
  for (int i = 0; i < 2000; ++i) {
    CHECK(sps::expected_improvement(model, random_point(d, probe, 0.0, 1.0), best_mean) <=
          best * (1.0 + 1e-9));
  }
}

TEST_CASE("the SPS plane: centre x+, vertex x_EI, orthogonal v, inside the box", "[plane]") {
  const int d = 6;
  const auto model = fitted_model(d, 6, 24);
  std::mt19937_64 rng(2);
  const auto [x_plus, best_mean, x_ei] = incumbent(model, rng);
  const sps::Plane plane =
      sps::sps_plane(model, x_plus, x_ei, best_mean, rng, sps::PlaneSearchSettings{});
  CHECK((plane.c - x_plus).norm() == Approx(0.0).margin(1e-15));
  CHECK((plane.c + plane.u - x_ei).norm() == Approx(0.0).margin(1e-12));
  CHECK(std::abs(plane.u.dot(plane.v)) < 1e-12);
  CHECK(plane.v.norm() > 1e-3);
  for (const Eigen::VectorXd& vertex :
       {Eigen::VectorXd(plane.c + plane.u), Eigen::VectorXd(plane.c - plane.u_neg_scale * plane.u),
        Eigen::VectorXd(plane.c + plane.v), Eigen::VectorXd(plane.c - plane.v)}) {
    CHECK(vertex.minCoeff() >= -1e-12);
    CHECK(vertex.maxCoeff() <= 1.0 + 1e-12);
  }
  // The optimized v scores at least as well as random orthogonal choices that fit in the box.
  const double chosen = sps::plane_acquisition(model, plane, best_mean);
  int compared = 0;
  int beaten = 0;
  for (int i = 0; i < 200 && compared < 20; ++i) {
    sps::Plane other = plane;
    other.v = std::max(0.05, rng() % 100 / 100.0) * plane.v.norm() *
              sps::random_orthogonal_direction(plane.u, rng);
    const Eigen::VectorXd hi = (plane.c + other.v).cwiseMax(plane.c - other.v);
    const Eigen::VectorXd lo = (plane.c + other.v).cwiseMin(plane.c - other.v);
    if (lo.minCoeff() < 0.0 || hi.maxCoeff() > 1.0) continue;
    ++compared;
    if (sps::plane_acquisition(model, other, best_mean) > chosen + 1e-12) ++beaten;
  }
  CHECK(compared >= 5);
  CHECK(beaten == 0);
}

TEST_CASE("opposite-vertex correction moves c - u onto the boundary", "[plane]") {
  sps::Plane plane;
  plane.c = Eigen::Vector2d(0.2, 0.5);
  plane.u = Eigen::Vector2d(0.6, 0.1);  // c - u = (-0.4, 0.4): outside
  plane.v = Eigen::Vector2d(-0.05, 0.3);
  sps::correct_opposite_vertex(plane);
  const Eigen::VectorXd opposite = plane.c - plane.u_neg_scale * plane.u;
  CHECK(plane.u_neg_scale == Approx(0.2 / 0.6));
  CHECK(opposite(0) == Approx(0.0).margin(1e-15));
  // The grid corner (-1,-1) is the corrected vertex; c + u is untouched.
  CHECK((plane.point(-1, -1) - opposite).norm() < 1e-15);
  CHECK((plane.point(1, 1) - (plane.c + plane.u)).norm() < 1e-15);
}
