// Degenerate use must never produce NaN, an exception or a plane outside the box.
#include <random>

#include <catch2/catch.hpp>

#include "sps/plane_search.hpp"
#include "sps/zoom_grid.hpp"

namespace {

void require_valid(const sps::PlaneSearch& s) {
  const sps::Plane& p = s.current_plane();
  REQUIRE(p.c.allFinite());
  REQUIRE(p.u.allFinite());
  REQUIRE(p.v.allFinite());
  REQUIRE(p.u_neg_scale >= 0.0);
  REQUIRE(p.u_neg_scale <= 1.0);
  if (s.options().method != sps::Method::kSpsRandom) {
    // The paper's random planes have unit-length diagonals and are clamped when shown; every
    // other plane lies inside the box.
    const double tol = 1e-9;
    for (const Eigen::VectorXd& vertex :
         {Eigen::VectorXd(p.c + p.u), Eigen::VectorXd(p.c - p.u_neg_scale * p.u),
          Eigen::VectorXd(p.c + p.v), Eigen::VectorXd(p.c - p.v)}) {
      REQUIRE(vertex.minCoeff() >= -tol);
      REQUIRE(vertex.maxCoeff() <= 1.0 + tol);
    }
  }
  for (const auto& cell : sps::grid_points(p, 3, std::vector<sps::GridCell>{})) {
    REQUIRE(cell.x.allFinite());
    REQUIRE(cell.x.minCoeff() >= 0.0);
    REQUIRE(cell.x.maxCoeff() <= 1.0);
  }
  const Eigen::VectorXd probe = Eigen::VectorXd::Constant(s.dims(), 0.37);
  REQUIRE(std::isfinite(s.posterior_mean(probe)));
  REQUIRE(std::isfinite(s.posterior_variance(probe)));
  REQUIRE(std::isfinite(s.expected_improvement(probe)));
}

sps::SearchOptions options(int dims, sps::Method m = sps::Method::kSps) {
  sps::SearchOptions o;
  o.dims = dims;
  o.seed = 17;
  o.method = m;
  return o;
}

}  // namespace

TEST_CASE("the same point chosen again and again", "[robustness]") {
  for (sps::Method m : {sps::Method::kSps, sps::Method::kSpsRandom, sps::Method::kSls}) {
    sps::PlaneSearch s(options(6, m));
    const Eigen::VectorXd same = Eigen::VectorXd::Constant(6, 0.8);
    for (int i = 0; i < 30; ++i) {
      REQUIRE_NOTHROW(s.submit(same));
      require_valid(s);
    }
  }
}

TEST_CASE("the centre chosen every time", "[robustness]") {
  for (sps::Method m : {sps::Method::kSps, sps::Method::kSls}) {
    sps::PlaneSearch s(options(8, m));
    for (int i = 0; i < 30; ++i) {
      REQUIRE_NOTHROW(s.submit(s.current_plane().c));
      require_valid(s);
    }
  }
}

TEST_CASE("corners and faces of the box as choices", "[robustness]") {
  sps::PlaneSearch s(options(5));
  std::mt19937_64 rng(3);
  std::bernoulli_distribution coin(0.5);
  for (int i = 0; i < 20; ++i) {
    Eigen::VectorXd corner(5);
    for (int k = 0; k < 5; ++k) corner(k) = coin(rng) ? 1.0 : 0.0;
    REQUIRE_NOTHROW(s.submit(corner));
    require_valid(s);
  }
}

TEST_CASE("200 iterations of a long session", "[robustness][long]") {
  sps::PlaneSearch s(options(3));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    // A noisy user: a random point of the current plane.
    const sps::Plane& p = s.current_plane();
    REQUIRE_NOTHROW(s.submit(p.point(u(rng), u(rng)).cwiseMax(0.0).cwiseMin(1.0)));
    require_valid(s);
  }
  CHECK(s.iteration() == 200);
}

TEST_CASE("1 to 40 dimensions", "[robustness]") {
  for (int d : {1, 2, 3, 10, 25, 40}) {
    CAPTURE(d);
    sps::PlaneSearch s(options(d));
    require_valid(s);
    std::mt19937_64 rng(static_cast<unsigned>(d));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 6; ++i) {
      const sps::Plane& p = s.current_plane();
      REQUIRE_NOTHROW(s.submit(p.point(u(rng), u(rng)).cwiseMax(0.0).cwiseMin(1.0)));
      require_valid(s);
    }
  }
}
