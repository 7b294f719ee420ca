#include <random>

#include <catch2/catch.hpp>

#include "common/first_difference.hpp"

#include "sps/plane_search.hpp"
#include "testing/simulated_user.hpp"
#include "testing/test_functions.hpp"

namespace {

bool same_plane(const sps::Plane& a, const sps::Plane& b) {
  return a.c == b.c && a.u == b.u && a.v == b.v && a.u_neg_scale == b.u_neg_scale;
}

sps::SearchOptions options(int dims, std::uint64_t seed, sps::Method m = sps::Method::kSps) {
  sps::SearchOptions o;
  o.dims = dims;
  o.seed = seed;
  o.method = m;
  return o;
}

}  // namespace

TEST_CASE("the first plane is a square centred at 0.5 inside the box", "[search]") {
  for (int d : {2, 5, 10}) {
    const sps::PlaneSearch search(options(d, 3));
    const sps::Plane& p = search.current_plane();
    CHECK((p.c.array() == 0.5).all());
    CHECK(p.u.norm() == Approx(p.v.norm()));
    CHECK(std::abs(p.u.dot(p.v)) < 1e-12);
    for (double sign : {-1.0, 1.0}) {
      CHECK((p.c + sign * p.u).minCoeff() >= -1e-12);
      CHECK((p.c + sign * p.u).maxCoeff() <= 1.0 + 1e-12);
      CHECK((p.c + sign * p.v).minCoeff() >= -1e-12);
      CHECK((p.c + sign * p.v).maxCoeff() <= 1.0 + 1e-12);
    }
  }
}

TEST_CASE("the same seed and the same choices give the same planes", "[search][determinism]") {
  const auto g = sps::make_test_function("gaussian", 4);
  sps::PlaneSearch a(options(4, 42));
  sps::PlaneSearch b(options(4, 42));
  for (int i = 0; i < 6; ++i) {
    REQUIRE(same_plane(a.current_plane(), b.current_plane()));
    const auto answer = sps::zoom_user(*g, a.current_plane());
    a.submit(answer.chosen, answer.comparisons);
    b.submit(answer.chosen, answer.comparisons);
  }
  CHECK(same_plane(a.current_plane(), b.current_plane()));
  sps::PlaneSearch c(options(4, 43));
  CHECK_FALSE(same_plane(a.current_plane(), c.current_plane()));
}

TEST_CASE("JSON round trip is exact and the restored search proposes the same planes",
          "[search][json]") {
  const auto g = sps::make_test_function("rosenbrock", 5);
  for (sps::Method m : {sps::Method::kSps, sps::Method::kSpsRandom, sps::Method::kSls}) {
    sps::PlaneSearch original(options(5, 7, m));
    for (int i = 0; i < 4; ++i)
      original.submit(sps::argmax_user(*g, original.current_plane(), 64).chosen);
    const std::string text = original.to_json();
    sps::PlaneSearch restored = sps::PlaneSearch::from_json(text);
    CHECK(test_support::first_difference(restored.to_json(), text) == "");
    CHECK(restored.iteration() == original.iteration());
    const Eigen::VectorXd probe = Eigen::VectorXd::Constant(5, 0.4);
    CHECK(restored.posterior_mean(probe) == Approx(original.posterior_mean(probe)).margin(1e-12));
    CHECK(restored.posterior_variance(probe) ==
          Approx(original.posterior_variance(probe)).margin(1e-12));
    for (int i = 0; i < 3; ++i) {
      const auto answer = sps::argmax_user(*g, original.current_plane(), 64);
      original.submit(answer.chosen);
      restored.submit(answer.chosen);
      REQUIRE(same_plane(original.current_plane(), restored.current_plane()));
    }
    // Undo works across the round trip too.
    REQUIRE(restored.undo());
    REQUIRE(original.undo());
    CHECK(same_plane(original.current_plane(), restored.current_plane()));
  }
}

TEST_CASE("JSON round trip of a long session whose model uses a window of the data",
          "[search][json]") {
  const auto g = sps::make_test_function("gaussian", 4);
  sps::SearchOptions o = options(4, 9);
  o.model.max_points = 24;  // small, so that a few planes already slide the window
  sps::PlaneSearch original(o);
  for (int i = 0; i < 8; ++i) {
    const auto answer = sps::zoom_user(*g, original.current_plane());
    original.submit(answer.chosen, answer.comparisons);
  }
  REQUIRE(original.data().point_count() > 24);
  REQUIRE(original.model().point_count() <= 24);
  const std::string text = original.to_json();
  sps::PlaneSearch restored = sps::PlaneSearch::from_json(text);
  CHECK(test_support::first_difference(restored.to_json(), text) == "");
  const auto answer = sps::zoom_user(*g, original.current_plane());
  original.submit(answer.chosen, answer.comparisons);
  restored.submit(answer.chosen, answer.comparisons);
  CHECK(same_plane(original.current_plane(), restored.current_plane()));
  for (int i = 0; i < 3; ++i) {
    REQUIRE(restored.undo());
    REQUIRE(original.undo());
    CHECK(same_plane(original.current_plane(), restored.current_plane()));
  }
}

TEST_CASE("corrupt state text is reported, not crashed on", "[search][json]") {
  CHECK_THROWS_AS(sps::PlaneSearch::from_json("{not json"), std::runtime_error);
  CHECK_THROWS_AS(sps::PlaneSearch::from_json("{}"), std::runtime_error);
  sps::PlaneSearch s(options(3, 1));
  s.submit(s.current_plane().c + 0.5 * s.current_plane().u);
  std::string text = s.to_json();
  const auto pos = text.find("\"latent\":[");
  REQUIRE(pos != std::string::npos);
  text.insert(pos + 10, "1e999,");  // an infinity, and one entry too many
  CHECK_THROWS_AS(sps::PlaneSearch::from_json(text), std::runtime_error);
}

TEST_CASE("undo returns to the previous plane; start over discards the data", "[search]") {
  const auto g = sps::make_test_function("gaussian", 3);
  sps::PlaneSearch s(options(3, 5));
  const sps::Plane first = s.current_plane();
  CHECK_FALSE(s.undo());
  s.submit(sps::argmax_user(*g, s.current_plane(), 64).chosen);
  const sps::Plane second = s.current_plane();
  const std::string after_one = s.to_json();
  s.submit(sps::argmax_user(*g, s.current_plane(), 64).chosen);
  REQUIRE(s.iteration() == 2);
  REQUIRE(s.undo());
  CHECK(same_plane(s.current_plane(), second));
  CHECK(test_support::first_difference(s.to_json(), after_one) == "");
  REQUIRE(s.undo());
  CHECK(same_plane(s.current_plane(), first));
  CHECK(s.data().point_count() == 0);
  s.submit(sps::argmax_user(*g, s.current_plane(), 64).chosen);
  s.start_over();
  CHECK(s.iteration() == 0);
  CHECK(s.data().point_count() == 0);
  CHECK((s.current_plane().c.array() == 0.5).all());
  CHECK(s.posterior_mean(Eigen::Vector3d(0.3, 0.3, 0.3)) == 0.0);
}

TEST_CASE("submit rejects malformed choices with a message", "[search]") {
  sps::PlaneSearch s(options(3, 5));
  CHECK_THROWS_AS(s.submit(Eigen::Vector2d(0.5, 0.5)), std::invalid_argument);
  CHECK_THROWS_AS(s.submit(Eigen::Vector3d(0.5, NAN, 0.5)), std::invalid_argument);
  CHECK(s.iteration() == 0);
}

TEST_CASE("SPS lowers the gap on the 5-D Gaussian within 10 iterations", "[search][integration]") {
  const auto g = sps::make_test_function("gaussian", 5);
  double first_total = 0.0;
  double last_total = 0.0;
  for (std::uint64_t seed : {1000u, 1001u, 1002u}) {
    sps::PlaneSearch s(options(5, seed));
    double best = -1.0;
    for (int i = 0; i < 10; ++i) {
      const auto answer = sps::argmax_user(*g, s.current_plane(), 160);
      best = std::max(best, (*g)(answer.chosen));
      if (i == 0) first_total += 1.0 - best;
      s.submit(answer.chosen);
    }
    last_total += 1.0 - best;
  }
  // The paper's curves drop by two orders of magnitude by iteration 10; ask for one.
  CHECK(last_total < 0.1 * first_total);
  CHECK(last_total / 3.0 < 2e-3);
}

TEST_CASE("SPS beats random planes and line search on Rosenbrock 10-D", "[search][integration]") {
  const auto g = sps::make_test_function("rosenbrock", 10);
  double total[3] = {0.0, 0.0, 0.0};
  const sps::Method methods[3] = {sps::Method::kSps, sps::Method::kSpsRandom, sps::Method::kSls};
  for (int m = 0; m < 3; ++m) {
    for (std::uint64_t seed : {1000u, 1001u, 1002u, 1003u}) {
      sps::PlaneSearch s(options(10, seed, methods[m]));
      double best = -1e300;
      for (int i = 0; i < 12; ++i) {
        const auto answer = sps::argmax_user(*g, s.current_plane(), 160);
        best = std::max(best, (*g)(answer.chosen));
        s.submit(answer.chosen);
      }
      total[m] += -best;
    }
  }
  CHECK(total[0] < total[1]);
  CHECK(total[0] < total[2]);
}

TEST_CASE("test functions reach their stated optimum and nowhere exceed it", "[functions]") {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& info : sps::available_functions()) {
    for (int d : {2, 7}) {
      const auto g = sps::make_test_function(info.name, d);
      CHECK((*g)(g->optimum_location()) == Approx(g->optimum_value()).margin(1e-9));
      for (int i = 0; i < 500; ++i) {
        Eigen::VectorXd x(d);
        for (int k = 0; k < d; ++k) x(k) = u(rng);
        CHECK((*g)(x) <= g->optimum_value() + 1e-9);
      }
    }
  }
  const auto moved = sps::make_test_function("gaussian", 3, 0.7);
  CHECK((*moved)(Eigen::Vector3d(0.7, 0.7, 0.7)) == Approx(1.0));
  CHECK_THROWS_AS(sps::make_test_function("rosenbrock", 3, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(sps::make_test_function("nope", 3), std::invalid_argument);
}
