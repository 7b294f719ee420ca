#include <catch2/catch.hpp>

#include "sps/zoom_grid.hpp"

namespace {

sps::Plane test_plane() {
  sps::Plane p;
  p.c = Eigen::Vector3d(0.5, 0.5, 0.5);
  p.u = Eigen::Vector3d(0.2, 0.1, 0.0);
  p.v = Eigen::Vector3d(-0.1, 0.2, 0.1);
  return p;
}

double dist(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm();
}

}  // namespace

TEST_CASE("coarsest grid: corners are the rhombus vertices, the centre is c", "[grid]") {
  const sps::Plane p = test_plane();
  for (int n : {3, 5}) {
    const auto cells = sps::grid_points(p, n, std::vector<sps::GridCell>{});
    REQUIRE(cells.size() == static_cast<std::size_t>(n * n));
    const auto at = [&](int col, int row) {
      return cells[static_cast<std::size_t>(row * n + col)].x;
    };
    CHECK(dist(at(n - 1, 0), p.c + p.u) < 1e-15);      // top right: (1, 1)
    CHECK(dist(at(0, n - 1), p.c - p.u) < 1e-15);      // bottom left: (-1, -1)
    CHECK(dist(at(n - 1, n - 1), p.c + p.v) < 1e-15);  // bottom right: (1, -1)
    CHECK(dist(at(0, 0), p.c - p.v) < 1e-15);          // top left: (-1, 1)
    CHECK(dist(at(n / 2, n / 2), p.c) < 1e-15);
    for (const auto& cell : cells) CHECK_FALSE(cell.clamped);
  }
}

TEST_CASE("rows of cells are evenly spaced straight lines (affine map)", "[grid]") {
  const sps::Plane p = test_plane();
  const auto cells = sps::grid_points(p, 5, std::vector<sps::GridCell>{});
  for (int row = 0; row < 5; ++row) {
    const Eigen::VectorXd step =
        cells[static_cast<std::size_t>(row * 5 + 1)].x - cells[static_cast<std::size_t>(row * 5)].x;
    for (int col = 1; col < 4; ++col) {
      const Eigen::VectorXd next = cells[static_cast<std::size_t>(row * 5 + col + 1)].x -
                                   cells[static_cast<std::size_t>(row * 5 + col)].x;
      CHECK((next - step).norm() < 1e-14);
    }
  }
}

TEST_CASE("zooming centres on the clicked cell and halves the spacing", "[grid]") {
  const sps::Plane p = test_plane();
  const int n = 3;
  const std::vector<sps::GridCell> path{{2, 0}, {0, 1}, {1, 2}, {1, 1}};
  std::vector<sps::GridCell> so_far;
  double spacing = 1.0;
  for (const auto& click : path) {
    const auto before = sps::grid_points(p, n, so_far);
    const Eigen::VectorXd clicked = before[static_cast<std::size_t>(click.row * n + click.col)].x;
    so_far.push_back(click);
    const sps::GridView view = sps::grid_view(n, so_far);
    spacing *= 0.5;
    CHECK(view.spacing == Approx(spacing));
    const auto after = sps::grid_points(p, n, so_far);
    CHECK(dist(after[4].x, clicked) < 1e-14);  // new centre cell = clicked cell
  }
  // The chosen point is the last clicked cell.
  const sps::GridPoint chosen = sps::chosen_point(p, n, path);
  const auto last_level =
      sps::grid_points(p, n, std::vector<sps::GridCell>(path.begin(), path.end() - 1));
  CHECK(dist(chosen.x,
             last_level[static_cast<std::size_t>(path.back().row * n + path.back().col)].x) <
        1e-15);
}

TEST_CASE("clicking an edge cell extrapolates past the rhombus", "[grid]") {
  const sps::Plane p = test_plane();
  // Top-right corner (c + u), then its top-right neighbour lies beyond the vertex.
  const auto cells = sps::grid_points(p, 3, std::vector<sps::GridCell>{{2, 0}});
  const sps::GridPoint& beyond = cells[2];
  CHECK(beyond.s == Approx(1.5));
  CHECK(beyond.t == Approx(1.5));
  CHECK(dist(beyond.x, p.c + 1.5 * p.u) < 1e-14);
  CHECK_FALSE(beyond.clamped);
}

TEST_CASE("points outside the unit box are clamped and flagged", "[grid]") {
  sps::Plane p;
  p.c = Eigen::Vector2d(0.9, 0.5);
  p.u = Eigen::Vector2d(0.1, 0.0);
  p.v = Eigen::Vector2d(0.0, 0.1);
  const auto cells = sps::grid_points(p, 3, std::vector<sps::GridCell>{{2, 0}, {2, 0}});
  int clamped = 0;
  for (const auto& cell : cells) {
    CHECK(cell.x.minCoeff() >= 0.0);
    CHECK(cell.x.maxCoeff() <= 1.0);
    if (cell.clamped) ++clamped;
  }
  CHECK(clamped > 0);
}

TEST_CASE("view interpolation goes continuously from one level to the next", "[grid]") {
  const sps::GridView a = sps::grid_view(3, {});
  const sps::GridView b = sps::grid_view(3, {{0, 0}});
  const sps::GridView start = sps::interpolate_views(a, b, 0.0);
  const sps::GridView end = sps::interpolate_views(a, b, 1.0);
  CHECK(start.s == Approx(a.s));
  CHECK(start.spacing == Approx(a.spacing));
  CHECK(end.s == Approx(b.s));
  CHECK(end.t == Approx(b.t));
  CHECK(end.spacing == Approx(b.spacing));
  double last_spacing = a.spacing;
  for (int i = 1; i <= 10; ++i) {
    const sps::GridView mid = sps::interpolate_views(a, b, i / 10.0);
    CHECK(mid.spacing < last_spacing);
    last_spacing = mid.spacing;
  }
}

TEST_CASE("bad grid input is rejected with a message", "[grid]") {
  CHECK_THROWS_AS(sps::grid_view(4, {}), std::invalid_argument);
  CHECK_THROWS_AS(sps::grid_view(3, {{3, 0}}), std::invalid_argument);
  CHECK_THROWS_AS(sps::chosen_point(test_plane(), 3, {}), std::invalid_argument);
}
