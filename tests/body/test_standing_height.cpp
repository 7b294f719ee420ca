// The standing height of a search point's body, checked by hand on a three-vertex model and
// against the tool's own measure on the built-in model.
#include <catch2/catch.hpp>

#include <cmath>

#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "body/standing_height.hpp"

namespace {

// Vertex 0 stays on the floor; vertex 1 stands 1.6 m high and component 0 lifts it by 0.1 m
// per beta; component 1 lowers vertex 2 (0.2 m above the floor) by 0.5 m per beta, so at
// large betas it becomes the lowest point.
body::Model three_vertex_model() {
  body::Model m;
  m.name = "three vertices";
  m.v_template = body::Vertices::Zero(3, 3);
  m.v_template(1, 1) = 1.6f;
  m.v_template(2, 1) = 0.2f;
  m.shapedirs = Eigen::MatrixXf::Zero(9, 2);
  m.shapedirs(3 * 1 + 1, 0) = 0.1f;
  m.shapedirs(3 * 2 + 1, 1) = -0.5f;
  return m;
}

}  // namespace

TEST_CASE("standing heights: lowest to highest vertex, linear in the betas", "[standing-height]") {
  const body::StandingHeights h(three_vertex_model());
  CHECK(h.dims() == 2);
  // x = 0.5 is beta = 0: the template, 1.6 m.
  CHECK(h.height_m(Eigen::Vector2d(0.5, 0.5)) == Approx(1.6).epsilon(1e-6));
  // beta0 = +3: vertex 1 at 1.9 m.
  CHECK(h.height_m(Eigen::Vector2d(1.0, 0.5)) == Approx(1.9).epsilon(1e-6));
  // beta1 = +3: vertex 2 at 0.2 - 1.5 = -1.3 m is the lowest point: 1.6 + 1.3.
  CHECK(h.height_m(Eigen::Vector2d(0.5, 1.0)) == Approx(2.9).epsilon(1e-6));
  CHECK(h.tallest_m({Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(1.0, 0.5)}) ==
        Approx(1.9).epsilon(1e-6));
  CHECK(h.tallest_m({}) == 0.0);
  CHECK_THROWS_AS(h.height_m(Eigen::Vector3d::Zero()), std::invalid_argument);
  body::Model empty;
  empty.name = "empty";
  CHECK_THROWS_AS(body::StandingHeights(empty), std::invalid_argument);
}

TEST_CASE("standing heights agree with the measured height of the built-in bodies",
          "[standing-height]") {
  const body::Model model = body::load_model("neutral", 10);
  const body::StandingHeights h(model);
  for (const double x0 : {0.1, 0.5, 0.9}) {
    Eigen::VectorXd x = Eigen::VectorXd::Constant(10, 0.5);
    x[0] = x0;
    x[3] = 1.0 - x0;
    const Eigen::VectorXf betas = (6.0 * x.array() - 3.0).cast<float>().matrix();
    INFO("x0 " << x0);
    CHECK(h.height_m(x) == Approx(body::measure(model, betas).height).margin(0.002));
  }
}
