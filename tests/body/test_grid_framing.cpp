// The band of heights a grid of bodies is framed on, checked on a column of vertices whose
// components move known parts of it.
#include <catch2/catch.hpp>

#include "body/grid_framing.hpp"

namespace {

// 19 vertices up a 1.8 m column, 0.1 m apart. Component 0 moves the "belly" (1.0-1.2 m)
// forward by 0.1 m per beta; component 1 lengthens the body, moving each vertex up by its
// height / 18 per beta (the head most, the feet not at all); component 2 moves the "shins"
// (0.2-0.3 m) forward.
body::Model column_model() {
  body::Model m;
  m.name = "column";
  const int v = 19;
  m.v_template = body::Vertices::Zero(v, 3);
  m.shapedirs = Eigen::MatrixXf::Zero(3 * v, 3);
  for (int i = 0; i < v; ++i) {
    const float y = 0.1f * static_cast<float>(i);
    m.v_template(i, 1) = y;
    if (i >= 10 && i <= 12) m.shapedirs(3 * i + 2, 0) = 0.1f;
    m.shapedirs(3 * i + 1, 1) = y / 18.0f;
    if (i >= 2 && i <= 3) m.shapedirs(3 * i + 2, 2) = 0.1f;
  }
  return m;
}

std::vector<Eigen::VectorXd> grid_along(int k, double half) {
  std::vector<Eigen::VectorXd> xs(3, Eigen::VectorXd::Constant(3, 0.5));
  xs[1][k] = 0.5 - half;
  xs[2][k] = 0.5 + half;
  return xs;
}

}  // namespace

TEST_CASE("grid framing: the band holds what moves, up to the tallest head", "[grid-framing]") {
  const body::GridFraming framing(column_model());
  const body::BandRule rule;
  // The mean body stands 1.8 m (x = 0.5: every beta 0).
  const auto belly = grid_along(0, 0.05);
  CHECK(framing.heights().height_m(belly[0]) == Approx(1.8).epsilon(1e-5));
  const body::FramedBand framed = framing.frame(belly);
  const body::HeightBand b = framed.band;
  CHECK(framed.tallest_m == Approx(framing.heights().tallest_m(belly)));
  CHECK(framing.band(belly).bottom_m == Approx(b.bottom_m));
  // From below the belly (1.0 m less the margin) to above the head; at least the least band.
  CHECK(b.top_m == Approx(1.8 + rule.margin_m).epsilon(1e-5));
  CHECK(
      b.bottom_m ==
      Approx(std::min(1.0 - rule.margin_m, 1.8 + rule.margin_m - rule.min_height_m)).epsilon(1e-5));
  const std::vector<int>& in_view = framed.vertices;
  CHECK(in_view.front() == 9);  // 0.9 m: the first vertex above the band's bottom (0.85 m)
  CHECK(in_view.back() == 18);
  // Longer bodies: the head moves most, the band is the least one under the tallest head.
  const auto taller = grid_along(1, 0.1);
  CHECK(framing.heights().tallest_m(taller) == Approx(1.8 + 0.6 * 0.1).epsilon(1e-4));
  const body::HeightBand t = framing.band(taller);
  CHECK(t.top_m == Approx(framing.heights().tallest_m(taller) + rule.margin_m).epsilon(1e-5));
  CHECK(t.height_m() == Approx(rule.min_height_m).epsilon(1e-5));
  // Shins that move: the band reaches the floor, the whole body.
  const body::HeightBand s = framing.band(grid_along(2, 0.05));
  CHECK(s.bottom_m == Approx(-rule.margin_m));
  CHECK(s.top_m == Approx(1.8 + rule.margin_m).epsilon(1e-5));
  // One body, or bodies that do not differ: the whole body.
  const std::vector<Eigen::VectorXd> one{Eigen::VectorXd::Constant(3, 0.5)};
  CHECK(framing.band(one).bottom_m == Approx(-rule.margin_m));
  const std::vector<Eigen::VectorXd> same(3, Eigen::VectorXd::Constant(3, 0.5));
  CHECK(framing.band(same).bottom_m == Approx(-rule.margin_m));
  // A point of the wrong size is an error naming it.
  CHECK_THROWS_AS(framing.band({Eigen::VectorXd::Constant(2, 0.5), Eigen::VectorXd::Zero(2)}),
                  std::invalid_argument);
}
