// The estimate of the design in mind (sps/target_estimate.hpp): its gradient, that it finds a
// target from a careful chooser's clicks, its prior alone, its validation, its use as the
// plane centre (saved with the search), its uncertainty and the planes along it.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sps/plane_construction.hpp"
#include "sps/plane_search.hpp"
#include "sps/target_estimate.hpp"
#include "test_support.hpp"

namespace {

// A 3-D search on uncertainty planes whose coordinates a person sees unequally.
sps::SearchOptions uncertainty_options(std::uint64_t seed) {
  sps::SearchOptions o;
  o.dims = 3;
  o.seed = seed;
  o.threads = 1;
  o.perceptual_scale = Eigen::Vector3d(200.0, 50.0, 20.0);
  o.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  return o;
}

sps::TargetModel model_for(const Eigen::VectorXd& scale,
                           const Eigen::MatrixXd& metric = Eigen::MatrixXd()) {
  sps::TargetModel m{sps::PerceptualMetric(scale, metric), {}};
  m.population.mean = Eigen::VectorXd::Constant(scale.size(), 0.5);
  m.population.sd = Eigen::VectorXd::Constant(scale.size(), 1.0 / 6.0);
  return m;
}

double distance_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                   const Eigen::VectorXd& scale) {
  return (a - b).cwiseProduct(scale).norm();
}

// "The shown point nearest the target (in mm) is preferred over the rest."
void add_nearest_choice(sps::PreferenceData& data, const std::vector<Eigen::VectorXd>& shown,
                        const Eigen::VectorXd& target, const Eigen::VectorXd& scale) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < shown.size(); ++k) {
    if (distance_mm(shown[k], target, scale) < distance_mm(shown[best], target, scale)) best = k;
  }
  std::vector<Eigen::VectorXd> others;
  for (std::size_t k = 0; k < shown.size(); ++k) {
    if (k != best) others.push_back(shown[k]);
  }
  data.add_preference(shown[best], others);
}

double metric_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::MatrixXd& m) {
  const Eigen::VectorXd d = a - b;
  return std::sqrt(d.dot(m * d));
}

// Grids of nine random points; the chooser takes the one nearest the target in the metric m
// (mm) over the others, as a person with the target in mind and a sharp eye would.
sps::PreferenceData careful_metric_choices(const Eigen::VectorXd& target, const Eigen::MatrixXd& m,
                                           int grids, std::mt19937_64& rng) {
  const Eigen::Index d = target.size();
  sps::PreferenceData data(static_cast<int>(d));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int g = 0; g < grids; ++g) {
    std::vector<Eigen::VectorXd> shown;
    std::size_t best = 0;
    for (std::size_t k = 0; k < 9; ++k) {
      Eigen::VectorXd x(d);
      for (Eigen::Index i = 0; i < d; ++i) x(i) = uniform(rng);
      shown.push_back(x);
      if (metric_mm(x, target, m) < metric_mm(shown[best], target, m)) best = k;
    }
    std::vector<Eigen::VectorXd> others;
    for (std::size_t k = 0; k < shown.size(); ++k) {
      if (k != best) others.push_back(shown[k]);
    }
    data.add_preference(shown[best], others);
  }
  return data;
}

// The same for a person who sees each coordinate on its own, `scale` mm per unit.
sps::PreferenceData careful_choices(const Eigen::VectorXd& target, const Eigen::VectorXd& scale,
                                    int grids, std::mt19937_64& rng) {
  return careful_metric_choices(target, scale.cwiseAbs2().asDiagonal().toDenseMatrix(), grids, rng);
}

// The point of the plane's 5x5 lattice (clamped into the box) nearest the goal: a careful
// chooser's click.
Eigen::VectorXd nearest_on_plane(const sps::Plane& p, const Eigen::VectorXd& goal,
                                 const Eigen::VectorXd& scale) {
  Eigen::VectorXd best = p.c;
  for (double s = -1.0; s <= 1.0; s += 0.5) {
    for (double t = -1.0; t <= 1.0; t += 0.5) {
      const Eigen::VectorXd x = p.point(s, t).cwiseMax(0.0).cwiseMin(1.0);
      if (distance_mm(x, goal, scale) < distance_mm(best, goal, scale)) best = x;
    }
  }
  return best;
}

// The log posterior's gradient at t against central differences, coordinate by coordinate.
void check_gradient(const sps::PreferenceData& data, const sps::TargetModel& m,
                    const Eigen::VectorXd& t) {
  Eigen::VectorXd grad;
  sps::target_log_posterior(data, m, t, &grad);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const double h = 1e-6;
    const Eigen::VectorXd step = h * Eigen::VectorXd::Unit(t.size(), k);
    const double fd = (sps::target_log_posterior(data, m, t + step) -
                       sps::target_log_posterior(data, m, t - step)) /
                      (2.0 * h);
    INFO("coordinate " << k << " at " << t.transpose());
    CHECK(grad(k) == Approx(fd).epsilon(1e-4).margin(1e-4));
  }
}

}  // namespace

TEST_CASE("the target log posterior's gradient matches finite differences", "[target]") {
  const Eigen::Vector4d scale(300.0, 60.0, 30.0, 10.0);
  std::mt19937_64 rng(7);
  const sps::PreferenceData data =
      careful_choices(Eigen::Vector4d(0.3, 0.6, 0.5, 0.8), scale, 12, rng);
  const sps::TargetModel m = model_for(scale);
  for (const Eigen::Vector4d& t :
       {Eigen::Vector4d(0.5, 0.5, 0.5, 0.5), Eigen::Vector4d(0.2, 0.7, 0.4, 0.9)}) {
    check_gradient(data, m, t);
  }
}

TEST_CASE("the target estimate finds the design a careful chooser has in mind", "[target]") {
  const Eigen::Vector4d scale(300.0, 60.0, 30.0, 10.0);
  const Eigen::Vector4d target(0.35, 0.62, 0.45, 0.55);
  std::mt19937_64 rng(11);
  const sps::PreferenceData data = careful_choices(target, scale, 60, rng);
  const sps::TargetModel m = model_for(scale);
  const Eigen::VectorXd estimate = sps::estimate_target(data, m, Eigen::Vector4d::Constant(0.5));
  const double before = distance_mm(m.population.mean, target, scale);
  const double after = distance_mm(estimate, target, scale);
  INFO("estimate " << estimate.transpose() << ", " << after << " mm from the target, the "
                   << "population mean " << before << " mm");
  CHECK(after < 0.3 * before);
  CHECK(after < 10.0);
  CHECK((estimate.array() >= 0.0).all());
  CHECK((estimate.array() <= 1.0).all());
}

TEST_CASE("without choices the target estimate is the population mean", "[target]") {
  sps::TargetModel m = model_for(Eigen::Vector3d(100.0, 50.0, 20.0));
  m.population.mean = Eigen::Vector3d(0.4, 0.5, 0.7);
  const sps::PreferenceData empty(3);
  CHECK(sps::estimate_target(empty, m, Eigen::Vector3d(0.9, 0.1, 0.2)).isApprox(m.population.mean));
}

TEST_CASE("a malformed target model is refused with a message", "[target]") {
  const sps::TargetModel good = model_for(Eigen::Vector3d(100.0, 50.0, 20.0));
  CHECK_NOTHROW(sps::validate_target_model(good, 3));
  CHECK_THROWS_AS(sps::validate_target_model(good, 4), std::invalid_argument);
  sps::TargetModel bad = good;
  bad.population.sd(1) = 0.0;
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("SD"));
  bad = good;
  bad.population.mean(2) = std::nan("");
  CHECK_THROWS_AS(sps::validate_target_model(bad, 3), std::invalid_argument);
  bad = good;
  bad.metric = sps::PerceptualMetric(Eigen::Vector2d(100.0, 50.0));
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("perceptual metric"));
  bad = good;
  bad.temperature_mm = 0.0;
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("temperature"));
}

TEST_CASE("with a population the plane is centred on the target estimate", "[target][search]") {
  // Random planes keep c = x+ exactly (SPS planes may shift it to keep the plane in the box).
  sps::SearchOptions o;
  o.dims = 3;
  o.seed = 5;
  o.method = sps::Method::kSpsRandom;
  o.threads = 1;
  o.perceptual_scale = Eigen::Vector3d(200.0, 50.0, 20.0);
  sps::PlaneSearch search(o);
  const sps::TargetModel m = model_for(o.perceptual_scale);
  search.set_population(m.population);
  const Eigen::Vector3d goal(0.3, 0.6, 0.45);
  for (int it = 0; it < 4; ++it) {
    search.submit(nearest_on_plane(search.current_plane(), goal, o.perceptual_scale));
    // The centre maximizes the target posterior: no better value nearby.
    const Eigen::VectorXd c = search.current_plane().c;
    Eigen::VectorXd grad;
    const double at_c = sps::target_log_posterior(search.data(), m, c, &grad);
    for (Eigen::Index k = 0; k < 3; ++k) {
      for (double h : {-1e-3, 1e-3}) {
        const Eigen::VectorXd nearby =
            (c + h * Eigen::Vector3d::Unit(k)).cwiseMax(0.0).cwiseMin(1.0);
        CHECK(sps::target_log_posterior(search.data(), m, nearby) <= at_c + 1e-9);
      }
    }
  }
  // Saved with the search: the restored one proposes the same plane.
  auto restored = sps::PlaneSearch::from_json(search.to_json());
  REQUIRE(restored.options().population.mean.size() == 3);
  CHECK(restored.options().population.sd.isApprox(m.population.sd));
  CHECK(restored.options().choice_temperature_mm == Approx(3.0));
  auto a = search;
  a.submit(a.current_plane().c);
  restored.submit(restored.current_plane().c);
  CHECK((a.current_plane().c - restored.current_plane().c).norm() < 1e-9);
  // Validated.
  CHECK_THROWS_AS(search.set_population({Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.1, 0.1), {}}),
                  std::invalid_argument);
  CHECK_THROWS_AS(search.set_population({Eigen::Vector3d(0.5, 1.5, 0.5), m.population.sd, {}}),
                  std::invalid_argument);
}

namespace {

// Grids of nine points along coordinate 0 only (the others at the population mean), 1.5 mm
// apart: a choice among them says where the design lies along that coordinate and nothing
// about the others.
sps::PreferenceData choices_along_first(const Eigen::VectorXd& target, const Eigen::VectorXd& scale,
                                        int grids) {
  const Eigen::Index d = target.size();
  sps::PreferenceData data(static_cast<int>(d));
  for (int g = 0; g < grids; ++g) {
    std::vector<Eigen::VectorXd> shown;
    for (int k = 0; k < 9; ++k) {
      Eigen::VectorXd x = Eigen::VectorXd::Constant(d, 0.5);
      x(0) = 0.3 + 0.05 * k + 0.01 * g;
      shown.push_back(x);
    }
    add_nearest_choice(data, shown, target, scale);
  }
  return data;
}

}  // namespace

TEST_CASE(
    "the estimate's uncertainty is the prior's without choices and shrinks where they "
    "compared",
    "[target]") {
  const Eigen::Vector3d scale(30.0, 60.0, 20.0);
  const sps::TargetModel m = model_for(scale);
  const sps::PreferenceData none(3);
  const Eigen::MatrixXd prior =
      sps::target_posterior_covariance(none, m, Eigen::Vector3d::Constant(0.5));
  CHECK((prior - m.population.sd.cwiseAbs2().asDiagonal().toDenseMatrix()).norm() < 1e-12);

  const Eigen::Vector3d target(0.55, 0.5, 0.5);
  const sps::PreferenceData data = choices_along_first(target, scale, 6);
  const Eigen::VectorXd t = sps::estimate_target(data, m, Eigen::Vector3d::Constant(0.5));
  const Eigen::MatrixXd cov = sps::target_posterior_covariance(data, m, t);
  CHECK((cov - cov.transpose()).norm() < 1e-12);
  CHECK(cov.llt().info() == Eigen::Success);
  // Along coordinate 0 the choices told a lot; along 1 and 2 nothing (the prior's variance).
  CHECK(cov(0, 0) < 0.5 * prior(0, 0));
  CHECK(cov(1, 1) == Approx(prior(1, 1)).epsilon(0.02));
  CHECK(cov(2, 2) == Approx(prior(2, 2)).epsilon(0.02));
  CHECK_THROWS_AS(sps::target_posterior_covariance(data, m, Eigen::Vector2d(0.5, 0.5)),
                  std::invalid_argument);
}

TEST_CASE("an uncertainty plane spans the estimate's least certain directions as they look",
          "[target][plane]") {
  const Eigen::Vector3d scale(30.0, 60.0, 20.0);
  // Variances in box units; as seen (times scale^2): 0.01*900 = 9, 0.001*3600 = 3.6 and
  // 0.04*400 = 16: the most uncertain look is along coordinate 2, then 0.
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.01, 0.001, 0.04).asDiagonal();
  const Eigen::Vector3d c = Eigen::Vector3d::Constant(0.5);
  const auto made = sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 1.0);
  REQUIRE(made);
  const sps::Plane& p = *made;
  CHECK((p.c - c).norm() < 1e-12);
  CHECK(std::abs(p.u(2)) > 0.0);
  CHECK(std::abs(p.u(0)) + std::abs(p.u(1)) < 1e-9);
  CHECK(std::abs(p.v(0)) > 0.0);
  CHECK(std::abs(p.v(1)) + std::abs(p.v(2)) < 1e-9);
  CHECK(p.u.cwiseProduct(scale).norm() == Approx(2.0 * 4.0));  // 2 SD of sqrt(16)
  CHECK(p.v.cwiseProduct(scale).norm() == Approx(2.0 * 3.0));  // 2 SD of sqrt(9)
  // Never shorter than the smallest length.
  const sps::Plane longer =
      *sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 12.0);
  CHECK(longer.u.cwiseProduct(scale).norm() == Approx(12.0));
  CHECK(longer.v.cwiseProduct(scale).norm() == Approx(12.0));
  // Other pairs of axes: (1st, 3rd) is coordinates 2 and 1, (2nd, 3rd) 0 and 1; no 4th axis.
  const auto second = sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 1.0, 1);
  REQUIRE(second);
  CHECK(std::abs(second->u(0)) + std::abs(second->u(1)) < 1e-9);
  CHECK(std::abs(second->v(0)) + std::abs(second->v(2)) < 1e-9);
  CHECK(second->v.cwiseProduct(scale).norm() == Approx(2.0 * std::sqrt(3.6)));
  const auto third = sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 1.0, 2);
  REQUIRE(third);
  CHECK(std::abs(third->u(1)) + std::abs(third->u(2)) < 1e-9);
  CHECK(std::abs(third->v(0)) + std::abs(third->v(2)) < 1e-9);
  CHECK_FALSE(sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 1.0, 3));
  CHECK_FALSE(sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 2.0, 1.0, -1));
}

TEST_CASE("an uncertainty plane near a face of the box keeps its clamped cells apart",
          "[target][plane]") {
  const Eigen::Vector3d scale(100.0, 100.0, 100.0);
  // The most uncertain direction runs across the box; the centre is almost on its face.
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.09, 0.04, 0.0001).asDiagonal();
  const Eigen::Vector3d c(0.02, 0.5, 0.5);
  const double min_length = 20.0;
  const auto made = sps::uncertainty_plane(c, cov, sps::PerceptualMetric(scale), 3.0, min_length);
  REQUIRE(made);
  const sps::Plane& p = *made;
  // Clamped as the window shows them, no two cells of the first 3x3 grid coincide.
  std::vector<Eigen::VectorXd> cells;
  for (int s = -1; s <= 1; ++s) {
    for (int t = -1; t <= 1; ++t) {
      cells.push_back(p.point(s, t).cwiseMax(0.0).cwiseMin(1.0));
    }
  }
  double closest = 1e9;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = i + 1; j < cells.size(); ++j) {
      closest = std::min(closest, (cells[i] - cells[j]).cwiseProduct(scale).norm());
    }
  }
  CHECK(closest >= 0.5 * min_length);
  // Where the whole box shows less than that (1 mm per unit), there is no such plane.
  CHECK_FALSE(sps::uncertainty_plane(c, cov, sps::PerceptualMetric(Eigen::Vector3d::Ones()), 3.0,
                                     min_length));
  // The plane was moved (its centre is not the estimate), by whole cells: the estimate is a
  // cell of the first grid, an edge or a corner, and stays the plane's current best.
  CHECK((p.c - c).norm() > 0.05);
  CHECK_FALSE(p.best_is_centre());
  CHECK(std::abs(p.best_s - std::round(p.best_s)) < 1e-12);
  CHECK(std::abs(p.best_t - std::round(p.best_t)) < 1e-12);
  CHECK((p.best() - c).norm() < 1e-9);
  CHECK((p.c.array() >= 0.0).all());
  CHECK((p.c.array() <= 1.0).all());
  const auto at = sps::plane_coordinates(p, c);
  REQUIRE(at);
  CHECK(at->first == Approx(p.best_s).margin(1e-9));
  CHECK(at->second == Approx(p.best_t).margin(1e-9));
  // Away from the faces the plane stays centred on the estimate.
  const auto inside = sps::uncertainty_plane(Eigen::Vector3d::Constant(0.5), cov * 0.1,
                                             sps::PerceptualMetric(scale), 3.0, min_length);
  REQUIRE(inside);
  CHECK(inside->best_is_centre());
  CHECK((inside->c - Eigen::Vector3d::Constant(0.5)).norm() < 1e-12);
}

TEST_CASE("a point's grid coordinates on a plane", "[plane]") {
  sps::Plane p;
  p.c = Eigen::Vector3d(0.5, 0.5, 0.5);
  p.u = Eigen::Vector3d(0.2, 0.0, 0.0);
  p.v = Eigen::Vector3d(0.0, 0.1, 0.0);
  for (const auto& [s, t] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {-1.0, -1.0}, {1.0, 0.0}, {0.25, -0.5}, {-1.0, 1.0}}) {
    const auto at = sps::plane_coordinates(p, p.point(s, t));
    REQUIRE(at);
    CHECK(at->first == Approx(s).margin(1e-9));
    CHECK(at->second == Approx(t).margin(1e-9));
  }
  // Off the plane, or on it but outside its square: none.
  CHECK_FALSE(sps::plane_coordinates(p, Eigen::Vector3d(0.5, 0.5, 0.6)));
  CHECK_FALSE(sps::plane_coordinates(p, p.c + 1.5 * p.u));
  // The opposite-vertex correction scales the c - u half.
  p.u_neg_scale = 0.5;
  const auto corner = sps::plane_coordinates(p, p.point(-1.0, -1.0));
  REQUIRE(corner);
  CHECK(corner->first == Approx(-1.0));
  CHECK(corner->second == Approx(-1.0));
}

TEST_CASE("a part of a plane is the plane's grid there, with the current best in place",
          "[plane]") {
  sps::Plane p;
  p.c = Eigen::Vector3d(0.5, 0.5, 0.5);
  p.u = Eigen::Vector3d(0.4, 0.0, 0.1);
  p.v = Eigen::Vector3d(0.0, 0.3, 0.0);
  p.best_s = 0.0;
  p.best_t = 1.0;
  // The part around (0.5, 0.5), half as wide: the plane's quarter with s, t in [0, 1].
  const auto part = sps::plane_part(p, 0.5, 0.5, 0.5);
  REQUIRE(part);
  for (const auto& [s, t] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {-1.0, -1.0}, {1.0, -1.0}, {0.5, 0.25}, {1.0, 1.0}}) {
    CHECK((part->point(s, t) - p.point(0.5 + 0.5 * s, 0.5 + 0.5 * t)).norm() < 1e-12);
  }
  // The current best is the same design, now at the part's (-1, 1).
  CHECK(part->best_s == Approx(-1.0));
  CHECK(part->best_t == Approx(1.0));
  CHECK((part->best() - p.best()).norm() < 1e-12);
  // A part without the current best, a line, a non-affine plane, a bad width: none.
  CHECK_FALSE(sps::plane_part(p, -0.5, -0.5, 0.5));
  CHECK_FALSE(sps::plane_part(p, 0.5, 0.5, 0.0));
  CHECK_FALSE(sps::plane_part(p, 0.5, 0.5, std::numeric_limits<double>::quiet_NaN()));
  sps::Plane line = p;
  line.v = Eigen::Vector3d::Zero();
  CHECK_FALSE(sps::plane_part(line, 0.0, 0.5, 0.5));
  sps::Plane corrected = p;
  corrected.u_neg_scale = 0.5;
  CHECK_FALSE(sps::plane_part(corrected, 0.5, 0.5, 0.5));
  // PlaneSearch takes it as its plane, and saves it.
  sps::SearchOptions options;
  options.dims = 3;
  sps::PlaneSearch search(options);
  const sps::Plane before = search.current_plane();
  REQUIRE(search.replace_with_plane_part(0.0, 0.0, 0.5));
  CHECK((search.current_plane().u - 0.5 * before.u).norm() < 1e-12);
  CHECK((search.x_plus() - before.best()).norm() < 1e-12);
  const sps::PlaneSearch loaded = sps::PlaneSearch::from_json(search.to_json());
  CHECK((loaded.current_plane().u - search.current_plane().u).norm() < 1e-12);
  CHECK_FALSE(search.replace_with_plane_part(0.9, 0.9, 0.05));
}

TEST_CASE("a careful chooser's choices of a grid's centre bound the estimate's uncertainty",
          "[target]") {
  // Grids in coordinates 0 and 1, cells 30 mm apart (10 temperatures: the softmax is
  // saturated), the centre chosen every time: the design is within a cell of it along 0 and
  // 1, and nothing is known along 2.
  const sps::TargetModel without = model_for(Eigen::Vector3d(100.0, 100.0, 100.0));
  CHECK(without.region_slack_temperatures < 0.0);  // off unless a space asks for it
  sps::TargetModel with = without;
  with.region_slack_temperatures = 8.0;
  sps::PreferenceData data(3);
  for (int g = 0; g < 6; ++g) {
    std::vector<Eigen::VectorXd> others;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        if (a != 0 || b != 0) others.push_back(Eigen::Vector3d(0.5 + 0.3 * a, 0.5 + 0.3 * b, 0.5));
    data.add_preference(Eigen::Vector3d::Constant(0.5), others);
  }
  const Eigen::Vector3d t = Eigen::Vector3d::Constant(0.5);
  const Eigen::MatrixXd cw = sps::target_posterior_covariance(data, with, t);
  const Eigen::MatrixXd cn = sps::target_posterior_covariance(data, without, t);
  const double prior = std::pow(1.0 / 6.0, 2);
  // Without the regions the saturated choices leave nearly the prior's spread.
  CHECK(cn(0, 0) > 0.5 * prior);
  // With them the spread along 0 and 1 is of the order of a cell (sd under 30 mm = 0.3),
  // and along 2 it stays the prior's.
  CHECK(std::sqrt(cw(0, 0)) * 100.0 < 30.0);
  CHECK(std::sqrt(cw(1, 1)) * 100.0 < 30.0);
  CHECK(cw(0, 0) < 0.25 * cn(0, 0));
  CHECK(cw(2, 2) == Approx(cn(2, 2)).epsilon(1e-6));
  // More slack for a person who confuses near cells: less certain than a careful chooser.
  sps::TargetModel loose = with;
  loose.region_slack_temperatures = 20.0;
  CHECK(sps::target_posterior_covariance(data, loose, t)(0, 0) > cw(0, 0));
  // A slack the model cannot use is refused by name.
  loose.region_slack_temperatures = std::nan("");
  CHECK_THROWS_WITH(sps::validate_target_model(loose, 3), Catch::Contains("slack"));
}

TEST_CASE("uncertainty planes are centred on the estimate and saved with the search",
          "[target][search]") {
  const sps::SearchOptions o = uncertainty_options(9);
  sps::PlaneSearch search(o);
  const sps::TargetModel m = model_for(o.perceptual_scale);
  search.set_population(m.population);
  const Eigen::Vector3d goal(0.4, 0.6, 0.45);
  for (int it = 0; it < 3; ++it) {
    search.submit(nearest_on_plane(search.current_plane(), goal, o.perceptual_scale));
    const sps::Plane& next = search.current_plane();
    const Eigen::VectorXd estimate = sps::estimate_target(search.data(), m, next.c);
    // Through the estimate: at its centre, or slid along its own axes where clamped cells
    // would coincide (uncertainty_plane).
    Eigen::Matrix<double, 3, 2> axes;
    axes << next.u, next.v;
    const Eigen::Vector2d along = axes.colPivHouseholderQr().solve(estimate - next.c);
    CAPTURE(it, (next.c - estimate).norm());
    CHECK((axes * along - (estimate - next.c)).norm() < 1e-6);
    // Its axes are orthogonal as a person sees them.
    const Eigen::VectorXd su = next.u.cwiseProduct(o.perceptual_scale);
    const Eigen::VectorXd sv = next.v.cwiseProduct(o.perceptual_scale);
    CHECK(std::abs(su.dot(sv)) < 1e-9 * su.norm() * sv.norm());
  }
  // A design space's size for them is kept for the next planes and saved with the search;
  // sizes outside the ranges are refused and change nothing.
  search.set_uncertainty_size({2.5, 1.5, 8.0});
  CHECK_THROWS_AS(search.set_uncertainty_size({0.05, 1.0}), std::invalid_argument);
  CHECK_THROWS_AS(search.set_uncertainty_size({3.0, -1.0}), std::invalid_argument);
  CHECK_THROWS_AS(search.set_uncertainty_size({std::nan(""), 1.0}), std::invalid_argument);
  CHECK_THROWS_AS(search.set_uncertainty_size({2.5, 1.5, std::nan("")}), std::invalid_argument);
  CHECK(search.options().uncertainty_extent == Approx(2.5));
  CHECK(search.options().uncertainty_min_lengths == Approx(1.5));
  const auto restored = sps::PlaneSearch::from_json(search.to_json());
  CHECK(restored.options().plane_axes == sps::PlaneAxes::kTargetUncertainty);
  CHECK(restored.options().uncertainty_extent == Approx(2.5));
  CHECK(restored.options().uncertainty_min_lengths == Approx(1.5));
  CHECK(restored.options().choice_region_slack == Approx(8.0));
  auto j = nlohmann::json::parse(search.to_json());
  j["options"]["plane_axes"] = "sideways";
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("plane_axes"));
  j["options"].erase("plane_axes");  // a file from before: the paper's axes
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().plane_axes ==
        sps::PlaneAxes::kExpectedImprovement);
  j["options"]["choice_region_slack"] = 5000.0;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("choice_region_slack"));
  // A file's sizes meet the setter's rule (validate_uncertainty_size), not a copy of it.
  j["options"]["choice_region_slack"] = 8.0;
  j["options"]["uncertainty_extent"] = 0.05;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("uncertainty_extent"));
  j["options"]["uncertainty_extent"] = 2.5;
  j["options"]["uncertainty_min_lengths"] = 11.0;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()),
                    Catch::Contains("uncertainty_min_lengths"));
  j["options"]["uncertainty_min_lengths"] = 1.5;
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().uncertainty_min_lengths == Approx(1.5));
  j["options"].erase("choice_region_slack");  // a file from before: the default
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().choice_region_slack ==
        sps::SearchOptions{}.choice_region_slack);
}

namespace {

// Coordinates 0 and 1 change together (correlation 0.8), coordinate 2 on its own.
sps::TargetModel correlated_model_for(const Eigen::Vector3d& scale) {
  sps::TargetModel m = model_for(scale);
  m.population.sd = Eigen::Vector3d(0.2, 0.1, 0.15);
  m.population.correlation = Eigen::Matrix3d::Identity();
  m.population.correlation(0, 1) = m.population.correlation(1, 0) = 0.8;
  return m;
}

}  // namespace

TEST_CASE("a correlated population's prior: its precision, gradient and covariance", "[target]") {
  const Eigen::Vector3d scale(30.0, 60.0, 20.0);
  const sps::TargetModel m = correlated_model_for(scale);
  REQUIRE_NOTHROW(sps::validate_target_model(m, 3));
  const Eigen::Matrix3d covariance =
      m.population.sd.asDiagonal() * m.population.correlation * m.population.sd.asDiagonal();
  CHECK((sps::population_covariance(m.population) - covariance).norm() < 1e-12);
  const Eigen::MatrixXd precision = sps::population_precision(m.population);
  CHECK((precision * covariance - Eigen::Matrix3d::Identity()).norm() < 1e-9);
  // Without choices the estimate's uncertainty is the prior's covariance, correlation and all.
  const sps::PreferenceData none(3);
  CHECK((sps::target_posterior_covariance(none, m, Eigen::Vector3d::Constant(0.5)) - covariance)
            .norm() < 1e-9);
  // The gradient with choices, by finite differences.
  std::mt19937_64 rng(3);
  const sps::PreferenceData data = careful_choices(Eigen::Vector3d(0.3, 0.4, 0.7), scale, 10, rng);
  check_gradient(data, m, Eigen::Vector3d(0.45, 0.6, 0.35));
  // A choice that says "higher along 0" pulls the estimate up along 1 too, and leaves 2.
  sps::PreferenceData along(3);
  const Eigen::Vector3d high(0.75, 0.5, 0.5), low(0.25, 0.5, 0.5);
  for (int k = 0; k < 3; ++k) along.add_preference(high, {Eigen::Vector3d::Constant(0.5), low});
  const Eigen::VectorXd e = sps::estimate_target(along, m, Eigen::Vector3d::Constant(0.5));
  CHECK(e(0) > 0.55);
  CHECK(e(1) > 0.53);
  CHECK(e(2) == Approx(0.5).margin(1e-3));
  CHECK(sps::estimate_target(along, model_for(scale), Eigen::Vector3d::Constant(0.5))(1) ==
        Approx(0.5).margin(1e-3));
}

TEST_CASE("a malformed population correlation is refused with a message", "[target]") {
  const sps::TargetModel good = correlated_model_for(Eigen::Vector3d(30.0, 60.0, 20.0));
  sps::TargetModel bad = good;
  bad.population.correlation = Eigen::Matrix2d::Identity();
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("correlation"));
  bad = good;
  bad.population.correlation(0, 1) = 0.5;  // not symmetric
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("symmetric"));
  bad = good;
  bad.population.correlation(2, 2) = 2.0;
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("diagonal"));
  bad = good;
  bad.population.correlation(0, 1) = bad.population.correlation(1, 0) = 1.0;  // singular
  CHECK_THROWS_WITH(sps::validate_target_model(bad, 3), Catch::Contains("positive definite"));
  bad = good;
  bad.population.correlation(1, 2) = bad.population.correlation(2, 1) = std::nan("");
  CHECK_THROWS_AS(sps::validate_target_model(bad, 3), std::invalid_argument);
}

TEST_CASE("a correlated population gives the first plane its principal axes, saved and read back",
          "[target][search]") {
  sps::SearchOptions o;
  o.dims = 3;
  o.seed = 4;
  o.threads = 1;
  o.perceptual_scale = Eigen::Vector3d(40.0, 40.0, 40.0);
  o.min_plane_length = 5.0;
  o.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  sps::PlaneSearch search(o);
  const sps::TargetModel m = correlated_model_for(o.perceptual_scale);
  search.set_population(m.population);
  sps::Plane first;
  REQUIRE(search.use_visible_first_plane());
  first = search.current_plane();
  // The widest spread of S Cov S runs along coordinates 0 and 1 together (same sign).
  const Eigen::VectorXd u = first.u.normalized();
  CHECK(std::abs(u(2)) < 1e-6);
  CHECK(u(0) * u(1) > 0.0);
  CHECK(std::abs(u(0)) > 0.3);
  CHECK(std::abs(u(1)) > 0.3);
  // With independent coordinates, or the paper's axes, the most visible coordinates instead.
  sps::PlaneSearch independent(o);
  independent.set_population(model_for(o.perceptual_scale).population);
  REQUIRE(independent.use_visible_first_plane());
  const sps::Plane visible = sps::visible_first_plane(o.perceptual_scale);
  CHECK((independent.current_plane().u - visible.u).norm() < 1e-12);
  o.plane_axes = sps::PlaneAxes::kExpectedImprovement;
  sps::PlaneSearch paper(o);
  paper.set_population(m.population);
  REQUIRE(paper.use_visible_first_plane());
  CHECK((paper.current_plane().u - visible.u).norm() < 1e-12);

  // The correlation is saved; a file from before has none; a broken one is refused.
  search.submit(first.c);
  const auto restored = sps::PlaneSearch::from_json(search.to_json());
  REQUIRE(restored.options().population.correlation.rows() == 3);
  CHECK((restored.options().population.correlation - m.population.correlation).norm() < 1e-12);
  auto j = nlohmann::json::parse(search.to_json());
  j["options"]["population_correlation"][1] = 0.3;  // (0, 1) no longer equals (1, 0)
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("symmetric"));
  j["options"]["population_correlation"] = {1.0, 0.8};
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()),
                    Catch::Contains("population_correlation"));
  j["options"].erase("population_correlation");
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().population.correlation.size() == 0);
}

TEST_CASE("an uncertainty plane the person cannot tell apart gives way to the paper's plane",
          "[target][search]") {
  sps::SearchOptions o = uncertainty_options(12);
  sps::PlaneSearch search(o);
  o.plane_axes = sps::PlaneAxes::kExpectedImprovement;
  sps::PlaneSearch paper(o);
  const sps::TargetModel m = model_for(o.perceptual_scale);
  search.set_population(m.population);
  paper.set_population(m.population);
  const Eigen::Vector3d goal(0.4, 0.6, 0.45);
  const Eigen::VectorXd click = nearest_on_plane(search.current_plane(), goal, o.perceptual_scale);
  search.submit(click);
  paper.submit(click);
  const sps::Plane uncertain = search.current_plane();
  REQUIRE((uncertain.u - paper.current_plane().u).norm() > 1e-6);
  // Replaced by the plane the paper's axes give for the same choice, once.
  REQUIRE(search.replace_uncertainty_plane());
  CHECK((search.current_plane().c - paper.current_plane().c).norm() < 1e-9);
  CHECK((search.current_plane().u - paper.current_plane().u).norm() < 1e-9);
  CHECK((search.current_plane().v - paper.current_plane().v).norm() < 1e-9);
  CHECK(search.options().plane_axes == sps::PlaneAxes::kTargetUncertainty);
  CHECK_FALSE(search.replace_uncertainty_plane());
  // Nothing to replace after an undo, nor for a search on the paper's axes.
  search.submit(click);
  REQUIRE(search.undo());
  CHECK_FALSE(search.replace_uncertainty_plane());
  CHECK_FALSE(paper.replace_uncertainty_plane());
}

TEST_CASE("uncertainty planes are at least the side the person needs, and keep it saved",
          "[target][search]") {
  sps::SearchOptions o = uncertainty_options(17);
  // Every direction visible enough that the sides below fit well inside the box.
  o.perceptual_scale = Eigen::Vector3d(400.0, 300.0, 250.0);
  // Half-diagonals of a fraction of the estimate's SD: the smallest side decides the planes.
  o.uncertainty_extent = 0.3;
  const double floor_side = o.uncertainty_min_lengths * o.min_plane_length;  // 24
  o.uncertainty_min_side = 2.0 * floor_side;
  sps::PlaneSearch search(o);
  const sps::TargetModel m = model_for(o.perceptual_scale);
  search.set_population(m.population);
  const auto seen = [&](const Eigen::VectorXd& a) { return a.cwiseProduct(o.perceptual_scale); };
  const Eigen::Vector3d goal(0.45, 0.55, 0.5);
  for (int it = 0; it < 8; ++it) {
    search.submit(nearest_on_plane(search.current_plane(), goal, o.perceptual_scale));
    const sps::Plane& plane = search.current_plane();
    CAPTURE(it, seen(plane.u).norm(), seen(plane.v).norm());
    CHECK(seen(plane.u).norm() >= 0.999 * o.uncertainty_min_side);
    CHECK(seen(plane.v).norm() >= 0.999 * o.uncertainty_min_side);
  }
  // Without the bound the same clicks give planes shorter than it: the bound is what held them.
  o.uncertainty_min_side = 0.0;
  sps::PlaneSearch plain(o);
  plain.set_population(m.population);
  double shortest = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 8; ++it) {
    plain.submit(nearest_on_plane(plain.current_plane(), goal, o.perceptual_scale));
    shortest = std::min(shortest, seen(plain.current_plane().v).norm());
  }
  CHECK(shortest < 0.9 * 2.0 * floor_side);
  // Refused outside [0, 10000], and nothing changes.
  CHECK_THROWS_AS(search.set_uncertainty_min_side(-1.0), std::invalid_argument);
  CHECK_THROWS_AS(search.set_uncertainty_min_side(std::nan("")), std::invalid_argument);
  CHECK(search.options().uncertainty_min_side == Approx(2.0 * floor_side));
  search.set_uncertainty_min_side(30.0);
  // Saved with the search; a file from before it has no such bound.
  const auto restored = sps::PlaneSearch::from_json(search.to_json());
  CHECK(restored.options().uncertainty_min_side == Approx(30.0));
  auto j = nlohmann::json::parse(search.to_json());
  j["options"]["uncertainty_min_side"] = -3.0;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("uncertainty_min_side"));
  j["options"].erase("uncertainty_min_side");
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().uncertainty_min_side == 0.0);
}

TEST_CASE("a plane still not told apart gives way to the population's axes through its centre",
          "[target][search]") {
  sps::SearchOptions o = uncertainty_options(13);
  sps::PlaneSearch search(o);
  const sps::TargetModel m = model_for(o.perceptual_scale);
  search.set_population(m.population);
  const Eigen::Vector3d goal(0.4, 0.6, 0.45);
  search.submit(nearest_on_plane(search.current_plane(), goal, o.perceptual_scale));
  const sps::Plane before = search.current_plane();
  REQUIRE(search.replace_with_population_plane());
  const sps::Plane& after = search.current_plane();
  // The same centre where the plane fits the box (it is slid only near a face), new axes:
  // the population's covariance as a person sees it, its two longest axes, each at least the
  // smallest side long and perpendicular as seen.
  const auto seen = [&](const Eigen::VectorXd& a) { return a.cwiseProduct(o.perceptual_scale); };
  CHECK((after.c - before.c).norm() < 0.5 * (after.u.norm() + after.v.norm()));
  CHECK(((after.u - before.u).norm() > 1e-6 || (after.v - before.v).norm() > 1e-6));
  CHECK(std::abs(seen(after.u).dot(seen(after.v))) <
        1e-6 * seen(after.u).norm() * seen(after.v).norm());
  CHECK(seen(after.u).norm() >= 0.999 * o.uncertainty_min_lengths * o.min_plane_length);
  CHECK(seen(after.v).norm() >= 0.999 * o.uncertainty_min_lengths * o.min_plane_length);
  // Only the window's planes have it: not the paper's axes, random planes, or a line.
  o.plane_axes = sps::PlaneAxes::kExpectedImprovement;
  sps::PlaneSearch paper(o);
  paper.set_population(m.population);
  CHECK_FALSE(paper.replace_with_population_plane());
  o.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  o.method = sps::Method::kSpsRandom;
  sps::PlaneSearch random(o);
  random.set_population(m.population);
  CHECK_FALSE(random.replace_with_population_plane());
  // Without a population there are no axes to take.
  o.method = sps::Method::kSps;
  sps::PlaneSearch unknown(o);
  CHECK_FALSE(unknown.replace_with_population_plane());
}

namespace {

using sps_test::overlapping_metric;

}  // namespace

TEST_CASE("with a full metric the target log posterior's gradient matches finite differences",
          "[target][metric]") {
  const Eigen::Matrix3d m = overlapping_metric();
  const sps::TargetModel model = model_for(m.diagonal().cwiseSqrt(), m);
  CHECK_NOTHROW(sps::validate_target_model(model, 3));
  std::mt19937_64 rng(5);
  const sps::PreferenceData data =
      careful_metric_choices(Eigen::Vector3d(0.3, 0.7, 0.4), m, 12, rng);
  for (const Eigen::Vector3d& t :
       {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.2, 0.8, 0.6)}) {
    check_gradient(data, model, t);
  }
  // And it is not the diagonal's: the off-diagonal entries change the value.
  sps::TargetModel diagonal = model;
  diagonal.metric = sps::PerceptualMetric(m.diagonal().cwiseSqrt());
  const Eigen::Vector3d t(0.2, 0.8, 0.6);
  CHECK(std::abs(sps::target_log_posterior(data, model, t) -
                 sps::target_log_posterior(data, diagonal, t)) > 0.1);
  // A metric the model cannot use is refused by name.
  Eigen::Matrix3d asymmetric = m;
  asymmetric(0, 1) += 500.0;
  CHECK_THROWS_WITH(model_for(m.diagonal().cwiseSqrt(), asymmetric),
                    Catch::Contains("perceptual metric"));
}

TEST_CASE("a chooser who sees overlapping directions is found sooner with the full metric",
          "[target][metric]") {
  const Eigen::Matrix3d m = overlapping_metric();
  const sps::TargetModel full = model_for(m.diagonal().cwiseSqrt(), m);
  const sps::TargetModel diagonal = model_for(m.diagonal().cwiseSqrt());
  double full_total = 0.0, diagonal_total = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.15, 0.85);
    const Eigen::Vector3d target(uniform(rng), uniform(rng), uniform(rng));
    const sps::PreferenceData data = careful_metric_choices(target, m, 25, rng);
    const Eigen::Vector3d start = Eigen::Vector3d::Constant(0.5);
    full_total += metric_mm(sps::estimate_target(data, full, start), target, m);
    diagonal_total += metric_mm(sps::estimate_target(data, diagonal, start), target, m);
  }
  INFO("mean miss with the full metric " << full_total / 8 << " mm, with its diagonal "
                                         << diagonal_total / 8 << " mm");
  CHECK(full_total < 0.9 * diagonal_total);
}

TEST_CASE("an uncertainty plane in a full metric has axes orthogonal as a person sees them",
          "[target][plane][metric]") {
  const Eigen::Matrix3d m = overlapping_metric();
  const sps::PerceptualMetric metric(m.diagonal().cwiseSqrt(), m);
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.01, 0.02, 0.004).asDiagonal();
  const Eigen::Vector3d c = Eigen::Vector3d::Constant(0.5);
  const double extent = 1.0;
  const auto made = sps::uncertainty_plane(c, cov, metric, extent, 1.0);
  REQUIRE(made);
  const sps::Plane& p = *made;
  // u and v are orthogonal in M (not in the box's coordinates)...
  CHECK(std::abs(p.u.dot(m * p.v)) < 1e-9 * metric.length(p.u) * metric.length(p.v));
  // ...and as long as the two largest spreads of what is seen.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> seen(metric.seen_covariance(cov));
  CHECK(metric.length(p.u) == Approx(extent * std::sqrt(seen.eigenvalues()(2))));
  CHECK(metric.length(p.v) == Approx(extent * std::sqrt(seen.eigenvalues()(1))));
}

TEST_CASE("a search keeps its full perceptual metric in its file and refuses a broken one",
          "[target][search][metric]") {
  sps::SearchOptions o = uncertainty_options(4);
  const Eigen::Matrix3d m = overlapping_metric();
  o.perceptual_scale = m.diagonal().cwiseSqrt();
  sps::PlaneSearch search(o);
  search.set_population(model_for(o.perceptual_scale).population);
  search.set_perceptual_scale(o.perceptual_scale, m);
  CHECK((search.options().perceptual_metric - m).norm() < 1e-9 * m.norm());
  // A broken one changes nothing.
  Eigen::Matrix3d broken = m;
  broken(0, 2) = 1e6;
  CHECK_THROWS_WITH(search.set_perceptual_scale(o.perceptual_scale, broken),
                    Catch::Contains("perceptual metric"));
  CHECK((search.options().perceptual_metric - m).norm() < 1e-9 * m.norm());

  const Eigen::Vector3d goal(0.35, 0.6, 0.45);
  for (int it = 0; it < 2; ++it) {
    search.submit(nearest_on_plane(search.current_plane(), goal, o.perceptual_scale));
  }
  // The planes are orthogonal in the metric.
  const sps::Plane& next = search.current_plane();
  CHECK(std::abs(next.u.dot(m * next.v)) <
        1e-6 * std::sqrt(next.u.dot(m * next.u)) * std::sqrt(next.v.dot(m * next.v)));
  const auto restored = sps::PlaneSearch::from_json(search.to_json());
  CHECK((restored.options().perceptual_metric - m).norm() < 1e-9 * m.norm());
  CHECK((restored.current_plane().u - next.u).norm() < 1e-12);

  auto j = nlohmann::json::parse(search.to_json());
  j["options"]["perceptual_metric"][1] = j["options"]["perceptual_metric"][1].get<double>() * 3.0;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("perceptual metric"));
  j["options"]["perceptual_metric"] = {1.0, 2.0};
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("perceptual_metric"));
  j["options"].erase("perceptual_metric");  // a file from before: the scale alone
  CHECK(sps::PlaneSearch::from_json(j.dump()).options().perceptual_metric.size() == 0);
  // Without a scale there is no metric either.
  search.set_perceptual_scale(Eigen::VectorXd());
  CHECK(search.options().perceptual_metric.size() == 0);
}

TEST_CASE("a plane moved to fit the box keeps the person's estimate as its current best, saved",
          "[target][search]") {
  sps::SearchOptions o;
  o.dims = 3;
  o.seed = 9;
  o.threads = 1;
  o.perceptual_scale = Eigen::Vector3d(100.0, 100.0, 100.0);
  o.min_plane_length = 20.0;
  o.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  sps::PlaneSearch search(o);
  sps::Population population = model_for(o.perceptual_scale).population;
  population.sd = Eigen::Vector3d(0.4, 0.3, 0.2);
  search.set_population(population);
  REQUIRE(search.use_visible_first_plane());
  // A person who wants a design near a corner of the box (a photo edit near +95 on three
  // sliders), each time preferring it over what the plane shows.
  const Eigen::Vector3d chosen(0.98, 0.97, 0.98);
  for (int plane = 0; plane < 4; ++plane) {
    search.submit(chosen);
    // The current best is on the plane, at a cell of its first grid, whatever the centre.
    const sps::Plane& next = search.current_plane();
    CHECK((search.x_plus() - next.best()).norm() < 1e-12);
    CHECK(std::abs(next.best_s - std::round(next.best_s)) < 1e-9);
    CHECK(std::abs(next.best_t - std::round(next.best_t)) < 1e-9);
  }
  const Eigen::VectorXd estimate = search.x_plus();
  CHECK((estimate.array() > 0.8).all());
  // The population's widest axis runs along coordinate 0, across the near face: its plane
  // through the estimate is moved by whole cells and keeps the estimate as its current best.
  REQUIRE(search.replace_with_population_plane());
  const sps::Plane& p = search.current_plane();
  CHECK_FALSE(p.best_is_centre());
  CHECK((p.c - estimate).norm() > 0.05);
  CHECK((search.x_plus() - estimate).norm() < 1e-9);
  CHECK(std::abs(p.best_s - std::round(p.best_s)) < 1e-12);
  CHECK(std::abs(p.best_t - std::round(p.best_t)) < 1e-12);
  // Saved and read back with it; a file from before the field has the centre; a broken one
  // is refused.
  const auto restored = sps::PlaneSearch::from_json(search.to_json());
  CHECK((restored.x_plus() - estimate).norm() < 1e-9);
  auto j = nlohmann::json::parse(search.to_json());
  j["plane"].erase("best_s");
  j["plane"].erase("best_t");
  CHECK((sps::PlaneSearch::from_json(j.dump()).x_plus() - p.c).norm() < 1e-12);
  j["plane"]["best_s"] = 3.0;
  CHECK_THROWS_WITH(sps::PlaneSearch::from_json(j.dump()), Catch::Contains("best_s"));
}
