// The texture charts' packer (tools/default_model/uv_packing.hpp) on charts made here:
// squares, long strips and an L whose hollow a small square can take.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "default_model/uv_packing.hpp"

using default_model::ChartPacking;
using default_model::pack_charts;
using default_model::PackChart;
using Vec2 = Eigen::Vector2d;

namespace {

// A chart of unit-size squares (two triangles each) at the given integer cells, scaled.
PackChart cells_chart(const std::vector<std::array<int, 2>>& cells, double size) {
  PackChart c;
  for (const auto& [x, y] : cells) {
    const int base = static_cast<int>(c.points.size());
    c.points.push_back(size * Vec2(x, y));
    c.points.push_back(size * Vec2(x + 1, y));
    c.points.push_back(size * Vec2(x + 1, y + 1));
    c.points.push_back(size * Vec2(x, y + 1));
    c.triangles.push_back({base, base + 1, base + 2});
    c.triangles.push_back({base, base + 2, base + 3});
  }
  return c;
}

Vec2 placed(const ChartPacking& p, int chart, const Vec2& point) {
  return p.scale * (p.rotation[chart] * point + p.offset[chart]);
}

bool inside(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
}

// Every chart inside [0, 1]^2, turned rigidly (no mirror, no stretch), and no point inside one
// chart's triangle lying inside another's. Returns the share of the square the charts cover.
double check_packing(const std::vector<PackChart>& charts, const ChartPacking& p) {
  REQUIRE(p.rotation.size() == charts.size());
  double area = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const Eigen::Matrix2d& R = p.rotation[c];
    CHECK(std::abs(R.determinant() - 1.0) < 1e-9);
    CHECK((R.transpose() * R - Eigen::Matrix2d::Identity()).norm() < 1e-9);
    for (const Vec2& q : charts[c].points) {
      const Vec2 u = placed(p, static_cast<int>(c), q);
      CHECK(u.minCoeff() >= 0.0);
      CHECK(u.maxCoeff() <= 1.0);
    }
    for (const auto& t : charts[c].triangles) {
      const Vec2 a = placed(p, static_cast<int>(c), charts[c].points[t[0]]);
      const Vec2 b = placed(p, static_cast<int>(c), charts[c].points[t[1]]);
      const Vec2 d = placed(p, static_cast<int>(c), charts[c].points[t[2]]);
      area += 0.5 * std::abs((b - a).x() * (d - a).y() - (b - a).y() * (d - a).x());
    }
  }
  int overlaps = 0;
  for (std::size_t c = 0; c < charts.size(); ++c)
    for (const auto& t : charts[c].triangles) {
      const Vec2 centre =
          (charts[c].points[t[0]] + charts[c].points[t[1]] + charts[c].points[t[2]]) / 3.0;
      const Vec2 u = placed(p, static_cast<int>(c), centre);
      for (std::size_t o = 0; o < charts.size(); ++o) {
        if (o == c) continue;
        for (const auto& s : charts[o].triangles)
          if (inside(u, placed(p, static_cast<int>(o), charts[o].points[s[0]]),
                     placed(p, static_cast<int>(o), charts[o].points[s[1]]),
                     placed(p, static_cast<int>(o), charts[o].points[s[2]])))
            ++overlaps;
      }
    }
  CHECK(overlaps == 0);
  return area;
}

}  // namespace

TEST_CASE("pack_charts: charts in the unit square, turned rigidly, none overlapping", "[uv]") {
  std::vector<PackChart> charts;
  charts.push_back(cells_chart({{0, 0}, {1, 0}, {0, 1}, {1, 1}}, 0.2));  // a square
  std::vector<std::array<int, 2>> strip;
  for (int x = 0; x < 8; ++x) strip.push_back({x, 0});
  charts.push_back(cells_chart(strip, 0.1));  // a long strip
  charts.push_back(cells_chart(strip, 0.1));
  charts.push_back(cells_chart({{0, 0}}, 0.05));  // small pieces
  charts.push_back(cells_chart({{0, 0}}, 0.05));
  // A turned copy: its smallest box is found whatever way it lies.
  PackChart turned = cells_chart(strip, 0.1);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(0.6).toRotationMatrix();
  for (Vec2& q : turned.points) q = R * q + Vec2(3, -2);
  charts.push_back(turned);
  const ChartPacking p = pack_charts(charts);
  const double coverage = check_packing(charts, p);
  INFO("coverage " << coverage << ", " << p.cells << " cells a side");
  CHECK(coverage > 0.5);
}

TEST_CASE("pack_charts: a small chart goes into an L's hollow", "[uv]") {
  // An L of three cells and a square of one cell: together they make a 2 x 2 square, and a
  // packer of bounding boxes would need a 3 x 2 box (coverage 4/6 at best).
  std::vector<PackChart> charts;
  charts.push_back(cells_chart({{0, 0}, {1, 0}, {0, 1}}, 1.0));
  charts.push_back(cells_chart({{0, 0}}, 0.8));
  const ChartPacking p = pack_charts(charts, 64);
  const double coverage = check_packing(charts, p);
  INFO("coverage " << coverage);
  CHECK(coverage > 0.7);
}

TEST_CASE("pack_charts: no area is refused by name", "[uv]") {
  PackChart flat;
  flat.points = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  flat.triangles = {{0, 1, 2}};
  CHECK_THROWS_AS(pack_charts({flat}), std::invalid_argument);
}
