// Distances between bodies in millimetres, checked by hand on a three-vertex model.
#include <catch2/catch.hpp>

#include "body/shape_distance.hpp"

namespace {

// Component 0 moves vertex 1 along +x by 1 m per beta; component 1 moves vertex 2 along +y by
// 0.5 m per beta.
body::Model three_vertex_model() {
  body::Model m;
  m.name = "three vertices";
  m.v_template = body::Vertices::Zero(3, 3);
  m.shapedirs = Eigen::MatrixXf::Zero(9, 2);
  m.shapedirs(3 * 1 + 0, 0) = 1.0f;
  m.shapedirs(3 * 2 + 1, 1) = 0.5f;
  return m;
}

}  // namespace

TEST_CASE("shape distance: RMS and largest vertex distance by hand", "[shape-distance]") {
  const body::ShapeDistance d(three_vertex_model());
  CHECK(d.dims() == 2);
  CHECK(d.vertex_count() == 3);
  const Eigen::Vector2d a(0.5, 0.5);
  // x0 + 0.01: beta + 0.06, vertex 1 moves 60 mm; the others stay.
  const Eigen::Vector2d b(0.51, 0.5);
  CHECK(d.max_mm(a, b) == Approx(60.0).epsilon(1e-5));
  CHECK(d.rms_mm(a, b) == Approx(60.0 / std::sqrt(3.0)).epsilon(1e-5));
  CHECK(d.rms_mm(a, a) == 0.0);
  // Whole range of each coordinate: 6 m on one vertex, 3 m on another.
  const Eigen::VectorXd scale = d.direction_rms_mm();
  CHECK(scale(0) == Approx(6000.0 / std::sqrt(3.0)).epsilon(1e-5));
  CHECK(scale(1) == Approx(3000.0 / std::sqrt(3.0)).epsilon(1e-5));
  // The target at betas (0, 0) is x = (0.5, 0.5).
  const auto to_target = d.rms_to_betas_mm({a, b}, Eigen::Vector2f(0.0f, 0.0f));
  REQUIRE(to_target.size() == 2u);
  CHECK(to_target[0] == Approx(0.0).margin(1e-6));
  CHECK(to_target[1] == Approx(d.rms_mm(a, b)).epsilon(1e-5));
  CHECK_THROWS_AS(d.rms_to_betas_mm({a}, Eigen::Vector3f::Zero()), std::invalid_argument);
  // The largest visible shift to the target: the largest vertex distance, never below the RMS.
  const auto seen = d.max_to_betas_mm({a, b}, Eigen::Vector2f(0.0f, 0.0f));
  REQUIRE(seen.size() == 2u);
  CHECK(seen[0] == Approx(0.0).margin(1e-6));
  CHECK(seen[1] == Approx(d.max_mm(a, b)).epsilon(1e-5));
  CHECK(seen[1] >= to_target[1] * (1.0 - 1e-6));
  CHECK_THROWS_AS(d.max_to_betas_mm({a}, Eigen::Vector3f::Zero()), std::invalid_argument);
  CHECK_THROWS_AS(d.max_mm(a, Eigen::Vector3d::Zero()), std::invalid_argument);
}

TEST_CASE("shape distance: pairwise largest vertex distances", "[shape-distance]") {
  const body::ShapeDistance d(three_vertex_model());
  const std::vector<Eigen::VectorXd> xs{Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.5, 0.5),
                                        Eigen::Vector2d(0.6, 0.5), Eigen::Vector2d(0.6, 0.7)};
  const Eigen::MatrixXd m = d.pairwise_max_mm(xs);
  REQUIRE(m.rows() == 4);
  CHECK(m(0, 1) == Approx(0.0).margin(1e-6));  // identical bodies
  CHECK(m(0, 2) == Approx(600.0).epsilon(1e-5));
  CHECK(m(2, 3) == Approx(600.0).epsilon(1e-5));  // 0.2 * 6 * 0.5 m on vertex 2
  CHECK(m(0, 3) == Approx(600.0).epsilon(1e-5));  // the larger of 600 and 600
  CHECK(m(3, 0) == m(0, 3));
  CHECK(m(2, 2) == 0.0);
  CHECK_THROWS_AS(body::ShapeDistance(body::Model{}), std::invalid_argument);
}

TEST_CASE("shape distance: over some vertices only (a cell framed on part of the body)",
          "[shape-distance]") {
  const body::ShapeDistance d(three_vertex_model());
  // Vertex 1 moves 60 mm with x0 + 0.01, vertex 2 30 mm with x1 + 0.01.
  const std::vector<Eigen::VectorXd> xs{Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.51, 0.5),
                                        Eigen::Vector2d(0.5, 0.51)};
  const Eigen::MatrixXd all = d.pairwise_max_mm(xs);
  const Eigen::MatrixXd only_2 = d.pairwise_max_mm(xs, {2});
  const Eigen::MatrixXd none = d.pairwise_max_mm(xs, {});
  CHECK(all(0, 1) == Approx(60.0).epsilon(1e-5));
  CHECK(only_2(0, 1) == Approx(0.0).margin(1e-6));  // vertex 1 is out of view
  CHECK(only_2(0, 2) == Approx(30.0).epsilon(1e-5));
  CHECK(only_2(1, 2) == Approx(30.0).epsilon(1e-5));
  CHECK(only_2(2, 1) == only_2(1, 2));
  CHECK(none.cwiseAbs().maxCoeff() == 0.0);
  const Eigen::MatrixXd both = d.pairwise_max_mm(xs, {1, 2});
  CHECK((both - all).cwiseAbs().maxCoeff() < 1e-6);
  // To a target: the target at betas (0, 0) is x = (0.5, 0.5).
  const auto to_target = d.max_to_betas_mm(xs, Eigen::Vector2f(0.0f, 0.0f), {2});
  REQUIRE(to_target.size() == 3u);
  CHECK(to_target[0] == Approx(0.0).margin(1e-6));
  CHECK(to_target[1] == Approx(0.0).margin(1e-6));
  CHECK(to_target[2] == Approx(30.0).epsilon(1e-5));
  // A vertex the model does not have is an error, not a read past the end.
  CHECK_THROWS_AS(d.pairwise_max_mm(xs, {3}), std::invalid_argument);
  CHECK_THROWS_AS(d.max_to_betas_mm(xs, Eigen::Vector2f(0.0f, 0.0f), {-1}), std::invalid_argument);
}
