// Measurements of analytic shapes: a cylinder's girth is known exactly (its polygon's
// perimeter), and an arm beside the torso must not count.
#include <catch2/catch.hpp>

#include <cmath>

#include "body/convex_hull.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "npz_fixtures.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// Perimeter of a regular n-gon inscribed in a circle of radius r.
double polygon_girth(double r, int n) {
  return 2.0 * n * r * std::sin(kPi / n);
}

body::Model load_cylinder(const fixtures::Cylinder& c, const std::string& name) {
  const auto path = fixtures::scratch_dir("measure-" + name) / (name + ".npz");
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  return body::load_model(path, 2);
}

}  // namespace

TEST_CASE("convex hull and perimeter", "[measurements]") {
  std::vector<Eigen::Vector2d> pts = {{0, 0}, {2, 0}, {2, 1}, {0, 1}, {1, 0.5}, {1, 0}, {2, 0}};
  const auto hull = body::convex_hull(pts);
  CHECK(hull.size() == 4);  // the inner point and the collinear/duplicate points are dropped
  CHECK(body::polygon_perimeter(hull) == Approx(6.0));
  CHECK(body::hull_contains(hull, {1, 0.5}));
  CHECK_FALSE(body::hull_contains(hull, {3, 0.5}));
  // A concave "C" shape is measured like a tape: across the gap.
  std::vector<Eigen::Vector2d> c = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {0, 3}};
  CHECK(body::polygon_perimeter(body::convex_hull(c)) == Approx(12.0));
}

TEST_CASE("measure: a cylinder of known circumference", "[measurements]") {
  fixtures::Cylinder c;
  c.radius = 0.16;
  c.height = 1.75;
  c.segments = 48;
  const auto m = load_cylinder(c, "cyl");
  const double girth = polygon_girth(c.radius, c.segments);
  auto res = body::measure(m, Eigen::VectorXf());
  CHECK(res.height == Approx(1.75).epsilon(1e-6));
  CHECK(res.chest == Approx(girth).epsilon(1e-5));
  CHECK(res.waist == Approx(girth).epsilon(1e-5));
  CHECK(res.hips == Approx(girth).epsilon(1e-5));
  CHECK(res.chest_height >= 0.65 * 1.75 - 1e-9);
  CHECK(res.chest_height <= 0.75 * 1.75 + 1e-9);
  CHECK(res.waist_height <= 0.67 * 1.75 + 1e-9);
  CHECK(res.hips_height <= res.waist_height);

  // Any betas: radius x 1.25 and height x 0.9 scale the readings accordingly.
  Eigen::VectorXf betas(2);
  betas << 0.25f, -0.1f;
  res = body::measure(m, betas);
  CHECK(res.height == Approx(1.75 * 0.9).epsilon(1e-5));
  CHECK(res.waist == Approx(girth * 1.25).epsilon(1e-5));
  CHECK(res.hips == Approx(girth * 1.25).epsilon(1e-5));
}

TEST_CASE("measure: landmarks follow the tailoring definitions on a shaped torso",
          "[measurements]") {
  // A body of revolution with a bulge at 0.70 H (chest), a pinch at 0.60 H (waist) and a bulge
  // at 0.52 H (hips); each girth must be found at its own height.
  fixtures::Cylinder c;
  c.rings = 201;
  c.segments = 64;
  c.height = 1.0;
  c.base_y = 0.0;
  auto arrays = fixtures::cylinder_model(c);
  auto& vt = arrays["v_template"].values;
  auto radius_at = [](double t) {
    return 0.15 + 0.03 * std::exp(-std::pow((t - 0.70) / 0.03, 2)) -
           0.04 * std::exp(-std::pow((t - 0.60) / 0.03, 2)) +
           0.05 * std::exp(-std::pow((t - 0.52) / 0.03, 2));
  };
  for (std::size_t v = 0; v < vt.size() / 3; ++v) {
    const double y = vt[3 * v + 1];
    const double s = radius_at(y) / 0.15;
    vt[3 * v] *= s;
    vt[3 * v + 2] *= s;
  }
  const auto path = fixtures::scratch_dir("measure-shaped") / "shaped.npz";
  fixtures::write_npz(path, fixtures::encode_model(arrays));
  const auto m = body::load_model(path, 2);
  const auto res = body::measure(m, Eigen::VectorXf());
  CHECK(res.chest_height == Approx(0.70).margin(0.006));
  CHECK(res.waist_height == Approx(0.60).margin(0.006));
  CHECK(res.hips_height == Approx(0.52).margin(0.006));
  CHECK(res.chest == Approx(polygon_girth(radius_at(0.70), 64)).epsilon(2e-3));
  CHECK(res.waist == Approx(polygon_girth(radius_at(0.60), 64)).epsilon(2e-3));
  CHECK(res.hips == Approx(polygon_girth(radius_at(0.52), 64)).epsilon(2e-3));
}

TEST_CASE("measure: an arm beside the torso is not part of the girth", "[measurements]") {
  fixtures::Cylinder torso;
  torso.radius = 0.15;
  torso.height = 1.7;
  torso.base_y = 0.0;
  fixtures::Cylinder arm = torso;
  arm.radius = 0.04;
  arm.height = 0.8;
  arm.base_y = 0.7;
  const auto t = body::load_model(
      [&] {
        const auto p = fixtures::scratch_dir("measure-arm-t") / "t.npz";
        fixtures::write_npz(p, fixtures::encode_model(fixtures::cylinder_model(torso)));
        return p;
      }(),
      2);
  const auto a = body::load_model(
      [&] {
        const auto p = fixtures::scratch_dir("measure-arm-a") / "a.npz";
        fixtures::write_npz(p, fixtures::encode_model(fixtures::cylinder_model(arm)));
        return p;
      }(),
      2);
  // Merge: the arm moved 0.25 m to the side of the torso.
  body::BodyMesh mesh;
  const auto V1 = t.v_template.rows(), V2 = a.v_template.rows();
  mesh.vertices.resize(V1 + V2, 3);
  mesh.vertices.topRows(V1) = t.v_template;
  mesh.vertices.bottomRows(V2) = a.v_template;
  mesh.vertices.bottomRows(V2).col(0).array() += 0.25f;
  body::Model merged = t;
  merged.faces.resize(t.faces.rows() + a.faces.rows(), 3);
  merged.faces.topRows(t.faces.rows()) = t.faces;
  merged.faces.bottomRows(a.faces.rows()) = a.faces.array() + static_cast<std::uint32_t>(V1);
  const auto res = body::measure(merged, mesh);
  const double girth = polygon_girth(0.15, torso.segments);
  CHECK(res.chest == Approx(girth).epsilon(1e-4));
  CHECK(res.waist == Approx(girth).epsilon(1e-4));
  CHECK(res.hips == Approx(girth).epsilon(1e-4));
}

TEST_CASE("measure: the chest search stops where arms join the torso", "[measurements]") {
  // Radius jumps by 60% above 0.72 H, as a slice does where A-posed arms meet the armpits.
  fixtures::Cylinder c;
  c.rings = 201;
  c.segments = 64;
  c.height = 1.0;
  c.base_y = 0.0;
  auto arrays = fixtures::cylinder_model(c);
  auto& vt = arrays["v_template"].values;
  auto radius_at = [](double t) {
    return (t > 0.7225 ? 0.24 : 0.15) + 0.01 * std::exp(-std::pow((t - 0.70) / 0.02, 2));
  };
  for (std::size_t v = 0; v < vt.size() / 3; ++v) {
    const double s = radius_at(vt[3 * v + 1]) / 0.15;
    vt[3 * v] *= s;
    vt[3 * v + 2] *= s;
  }
  const auto path = fixtures::scratch_dir("measure-armpit") / "armpit.npz";
  fixtures::write_npz(path, fixtures::encode_model(arrays));
  const auto res = body::measure(body::load_model(path, 2), Eigen::VectorXf());
  CHECK(res.chest_height == Approx(0.70).margin(0.006));
  CHECK(res.chest == Approx(polygon_girth(0.16, 64)).epsilon(2e-3));
}
