// Measurements of analytic shapes: a cylinder's girth is known exactly (its polygon's
// perimeter), and an arm beside the torso must not count.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "body/convex_hull.hpp"
#include "body/measurements.hpp"
#include "body/mesh_slice.hpp"
#include "body/model_loader.hpp"
#include "npz_fixtures.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// Perimeter of a regular n-gon inscribed in a circle of radius r.
double polygon_girth(double r, int n) {
  return 2.0 * n * r * std::sin(kPi / n);
}

// A body of revolution 1 m tall standing on y = 0: the fixture cylinder (radius 0.15 m, 201
// rings, 64 segments) with each ring scaled to radius_at(its height).
template <typename RadiusAt>
body::Model load_revolution(const std::string& name, RadiusAt radius_at) {
  fixtures::Cylinder c;
  c.rings = 201;
  c.segments = 64;
  c.height = 1.0;
  c.base_y = 0.0;
  auto arrays = fixtures::cylinder_model(c);
  auto& vt = arrays["v_template"].values;
  for (std::size_t v = 0; v < vt.size() / 3; ++v) {
    const double s = radius_at(vt[3 * v + 1]) / c.radius;
    vt[3 * v] *= s;
    vt[3 * v + 2] *= s;
  }
  const auto path = fixtures::scratch_dir("measure-" + name) / (name + ".npz");
  fixtures::write_npz(path, fixtures::encode_model(arrays));
  return body::load_model(path, 2);
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
  CHECK(res.hips_height >= 0.45 * 1.75 - 1e-9);
  CHECK(res.hips_height <= 0.55 * 1.75 + 1e-9);

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
  auto radius_at = [](double t) {
    return 0.15 + 0.03 * std::exp(-std::pow((t - 0.70) / 0.03, 2)) -
           0.04 * std::exp(-std::pow((t - 0.60) / 0.03, 2)) +
           0.05 * std::exp(-std::pow((t - 0.52) / 0.03, 2));
  };
  const auto res = body::measure(load_revolution("shaped", radius_at), Eigen::VectorXf());
  CHECK(res.chest_height == Approx(0.70).margin(0.006));
  CHECK(res.waist_height == Approx(0.60).margin(0.006));
  CHECK(res.hips_height == Approx(0.52).margin(0.006));
  CHECK(res.chest == Approx(polygon_girth(radius_at(0.70), 64)).epsilon(2e-3));
  CHECK(res.waist == Approx(polygon_girth(radius_at(0.60), 64)).epsilon(2e-3));
  CHECK(res.hips == Approx(polygon_girth(radius_at(0.52), 64)).epsilon(2e-3));
}

TEST_CASE("measure: a belly larger than the seat gives a waist larger than the hips",
          "[measurements]") {
  // An apple-shaped trunk: the body of revolution widens from the seat (0.50 H) up to a belly
  // whose narrowest girth in the waist's range (0.56-0.67 H) is still larger than the seat's.
  // The hips stay the seat's girth, not the belly's (9% of ANSUR II's men are built so).
  auto radius_at = [](double t) {
    return 0.15 + 0.01 * std::exp(-std::pow((t - 0.50) / 0.03, 2)) +
           0.04 * std::exp(-std::pow((t - 0.62) / 0.08, 2));
  };
  const auto res = body::measure(load_revolution("apple", radius_at), Eigen::VectorXf());
  CHECK(res.waist > res.hips + 0.02);
  CHECK(res.hips_height >= 0.45 - 1e-9);
  CHECK(res.hips_height <= 0.55 + 1e-9);
  CHECK(res.hips == Approx(polygon_girth(radius_at(res.hips_height), 64)).epsilon(2e-3));
  CHECK(res.hips < polygon_girth(radius_at(0.62), 64) - 0.05);
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
  auto radius_at = [](double t) {
    return (t > 0.7225 ? 0.24 : 0.15) + 0.01 * std::exp(-std::pow((t - 0.70) / 0.02, 2));
  };
  const auto res = body::measure(load_revolution("armpit", radius_at), Eigen::VectorXf());
  CHECK(res.chest_height == Approx(0.70).margin(0.006));
  CHECK(res.chest == Approx(polygon_girth(0.16, 64)).epsilon(2e-3));
}

namespace {

// Appends a closed axis-aligned box [lo, hi] to a mesh, faces counter-clockwise seen from
// outside (or clockwise with `flip`).
void add_box(body::Vertices& v, body::Faces& f, const Eigen::Vector3f& lo,
             const Eigen::Vector3f& hi, bool flip = false) {
  const auto base = static_cast<std::uint32_t>(v.rows());
  v.conservativeResize(v.rows() + 8, 3);
  for (int i = 0; i < 8; ++i) {
    v.row(base + i) << ((i & 1) ? hi.x() : lo.x()), ((i & 2) ? hi.y() : lo.y()),
        ((i & 4) ? hi.z() : lo.z());
  }
  // Quads (outward normal): -x, +x, -y, +y, -z, +z.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    const std::uint32_t t[2][3] = {{base + q[0], base + q[1], base + q[2]},
                                   {base + q[0], base + q[2], base + q[3]}};
    for (const auto& tri : t) {
      f.conservativeResize(f.rows() + 1, 3);
      f.row(f.rows() - 1) << tri[0], (flip ? tri[2] : tri[1]), (flip ? tri[1] : tri[2]);
    }
  }
}

// A box figure: a torso 0.40 x 0.80 x 0.20 m on two legs 0.16 x 0.80 x 0.20 m (a 4 cm gap
// between them), with SMPL-named joints placed by hand.
struct BoxFigure {
  body::Model model;
  body::BodyMesh mesh;
};

BoxFigure box_figure(bool flip) {
  BoxFigure b;
  body::Vertices& v = b.mesh.vertices;
  body::Faces& f = b.model.faces;
  add_box(v, f, {-0.2f, 0.8f, -0.1f}, {0.2f, 1.6f, 0.1f}, flip);
  add_box(v, f, {-0.18f, 0.0f, -0.1f}, {-0.02f, 0.8f, 0.1f}, flip);
  add_box(v, f, {0.02f, 0.0f, -0.1f}, {0.18f, 0.8f, 0.1f}, flip);
  b.model.joint_names = body::smpl_joint_names();
  b.mesh.joints = body::Vertices::Zero(24, 3);
  const auto set = [&](const char* name, float x, float y, float z) {
    for (std::size_t j = 0; j < b.model.joint_names.size(); ++j) {
      if (b.model.joint_names[j] == name)
        b.mesh.joints.row(static_cast<Eigen::Index>(j)) << x, y, z;
    }
  };
  set("left_hip", 0.1f, 0.85f, 0.0f);
  set("right_hip", -0.1f, 0.85f, 0.0f);
  set("left_shoulder", 0.17f, 1.5f, 0.02f);
  set("right_shoulder", -0.17f, 1.5f, -0.02f);
  set("left_elbow", 0.30f, 1.25f, 0.0f);
  set("right_elbow", -0.30f, 1.25f, 0.0f);
  set("left_wrist", 0.34f, 1.0f, 0.03f);
  set("right_wrist", -0.34f, 1.0f, 0.03f);
  return b;
}

}  // namespace

TEST_CASE("measure: mass, BMI, shoulder width, inseam and arm length of a box figure",
          "[measurements]") {
  for (const bool flip : {false, true}) {
    CAPTURE(flip);
    const auto b = box_figure(flip);
    const auto m = body::measure(b.model, b.mesh);
    const double volume = 0.4 * 0.8 * 0.2 + 2 * 0.16 * 0.8 * 0.2;
    CHECK(m.height == Approx(1.6).epsilon(1e-6));
    CHECK(m.volume == Approx(volume).epsilon(1e-5));
    CHECK(m.mass == Approx(volume * body::kBodyDensity).epsilon(1e-5));
    CHECK(m.bmi == Approx(volume * body::kBodyDensity / (1.6 * 1.6)).epsilon(1e-5));
    // The acromia: the rays from the shoulder joints, 27 degrees out from straight up (in the
    // plane through both joints), leave the torso box through its sides at x = +-0.2 (they
    // would meet the top, y = 1.6, only farther out).
    const double angle = body::kAcromionAngleDegrees * M_PI / 180.0;
    const Eigen::Vector3d across = Eigen::Vector3d(0.34, 0.0, 0.04).normalized();
    const Eigen::Vector3d ray =
        std::cos(angle) * Eigen::Vector3d::UnitY() + std::sin(angle) * across;
    REQUIRE((0.2 - 0.17) / ray.x() < (1.6 - 1.5) / ray.y());
    const Eigen::Vector3d left_acromion =
        Eigen::Vector3d(0.17, 1.5, 0.02) + (0.2 - 0.17) / ray.x() * ray;
    // The right joint mirrors the left through the torso's axis: so does its acromion.
    const Eigen::Vector3d right_acromion(-left_acromion.x(), left_acromion.y(), -left_acromion.z());
    CHECK(left_acromion.y() > 1.5);
    CHECK(m.shoulder_width ==
          Approx(std::hypot(0.4, left_acromion.z() - right_acromion.z())).epsilon(1e-5));
    // The crotch is the torso's underside between the legs.
    CHECK(m.inseam == Approx(0.8).margin(1e-5));
    // Acromion - elbow - wrist: the right arm's is as long as the left's.
    const Eigen::Vector3d elbow(0.30, 1.25, 0.0), wrist(0.34, 1.0, 0.03);
    const double arm = (left_acromion - elbow).norm() + (elbow - wrist).norm();
    CHECK(m.arm_length == Approx(arm).epsilon(1e-5));
    // The same without the girths.
    const auto quick = body::measure(b.model, b.mesh, false);
    CHECK(quick.inseam == Approx(m.inseam).margin(1e-9));
    CHECK(quick.mass == Approx(m.mass).epsilon(1e-9));
    CHECK(quick.chest == 0.0);
  }
}

TEST_CASE("measure: lengths that need joints or legs are n/a without them", "[measurements]") {
  fixtures::Cylinder c;
  c.height = 1.75;
  c.base_y = 0.0;
  const auto m = load_cylinder(c, "cyl-noleg");
  const auto res = body::measure(m, Eigen::VectorXf());
  CHECK(std::isnan(res.inseam));  // no crotch: the ray meets only the sole
  auto b = box_figure(false);
  b.model.joint_names.assign(24, "joint");
  const auto nameless = body::measure(b.model, b.mesh);
  CHECK(std::isnan(nameless.shoulder_width));
  CHECK(std::isnan(nameless.arm_length));
  // Without hip joints the line through the mean vertex (x = 0) still finds the crotch.
  CHECK(nameless.inseam == Approx(0.8).margin(1e-5));
}

TEST_CASE("measurement names, formatting and typed values", "[measurements]") {
  REQUIRE(body::find_measurement("height") != nullptr);
  REQUIRE(body::find_measurement("shoulder_width") != nullptr);
  CHECK(body::find_measurement("weight") == nullptr);
  CHECK(body::measurement_kinds().size() == 14);
  using body::Quantity;
  using body::Units;
  CHECK(body::format_measurement(Quantity::kLength, 1.8, Units::kMetric) == "180.0 cm");
  CHECK(body::format_measurement(Quantity::kLength, 1.8, Units::kImperial) == "5 ft 10.9 in");
  // Rounding happens before feet and inches are split: 71.97 in is 6 ft 0.0 in.
  CHECK(body::format_measurement(Quantity::kLength, 71.97 * 0.0254, Units::kImperial) ==
        "6 ft 0.0 in");
  CHECK(body::format_measurement(Quantity::kLength, 0.9144, Units::kImperial) == "36.0 in");
  CHECK(body::format_measurement(Quantity::kMass, 90.0, Units::kImperial) == "198.4 lb");
  CHECK(body::format_measurement(Quantity::kMass, std::nan(""), Units::kMetric) == "n/a");
  CHECK(body::format_difference(Quantity::kLength, -0.0254, Units::kImperial) == "-1.00 in");
  CHECK(body::format_difference(Quantity::kLength, 0.012, Units::kMetric) == "+1.2 cm");
  CHECK(body::format_difference(Quantity::kMass, 1.26, Units::kMetric) == "+1.3 kg");
  CHECK(body::format_difference(Quantity::kMass, -0.4536, Units::kImperial) == "-1.0 lb");
  CHECK(body::format_measurement(Quantity::kBmi, 24.08, Units::kImperial) == "24.1");
  CHECK(body::format_difference(Quantity::kBmi, 0.5, Units::kMetric) == "+0.5");
  const auto& height = *body::find_measurement("height");
  const auto& mass = *body::find_measurement("mass");
  CHECK(body::parse_measurement_value(height, "1.80") == Approx(1.80));
  CHECK(body::parse_measurement_value(height, "180cm") == Approx(1.80));
  CHECK(body::parse_measurement_value(height, "71 in") == Approx(1.8034));
  CHECK(body::parse_measurement_value(mass, "198lb") == Approx(89.8113).epsilon(1e-5));
  // Feet and inches, as typed and as the imperial display writes them (a round trip).
  CHECK(body::parse_measurement_value(height, "5ft11in") == Approx(71 * 0.0254));
  CHECK(body::parse_measurement_value(height, "5'11\"") == Approx(71 * 0.0254));
  CHECK(body::parse_measurement_value(height, "5'11") == Approx(71 * 0.0254));
  CHECK(body::parse_measurement_value(height, "6 ft") == Approx(72 * 0.0254));
  CHECK(body::parse_measurement_value(height, "6'") == Approx(72 * 0.0254));
  CHECK(body::parse_measurement_value(height, "70\"") == Approx(70 * 0.0254));
  const std::string shown = body::format_measurement(Quantity::kLength, 1.8, Units::kImperial);
  CHECK(body::parse_measurement_value(height, shown) == Approx(1.8).margin(0.002));
  for (const char* bad : {"nan", "inf", "", "abc", "1.8kg", "-1.7", "0", "1e9", "1.8.2", "5ft13in",
                          "5ft-1in", "5ftxin", "5'11kg"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(body::parse_measurement_value(height, bad), std::invalid_argument);
  }
  CHECK_THROWS_WITH(body::parse_measurement_value(mass, "9000"),
                    Catch::Contains("mass") && Catch::Contains("out of range"));
}

TEST_CASE("slices at many heights in one pass equal the slices one at a time",
          "[measurements][slice]") {
  const body::Model model = body::load_builtin_model("neutral", 10);
  Eigen::VectorXf betas(10);
  betas << 1.5f, -2.0f, 0.5f, 2.5f, -1.0f, 0.0f, 3.0f, -3.0f, 0.7f, -0.2f;
  const body::BodyMesh mesh = body::evaluate(model, betas);
  const double ymin = mesh.vertices.col(1).minCoeff(), ymax = mesh.vertices.col(1).maxCoeff();
  std::vector<double> heights;
  // Descending, a repeat, a vertex's own height (the at-or-above rule), outside the body.
  for (int i = 160; i >= 20; i -= 7) heights.push_back(ymin + (ymax - ymin) * i / 200.0);
  heights.push_back(heights[3]);
  heights.push_back(mesh.vertices(0, 1));
  heights.push_back(ymax + 1.0);
  const auto all = body::slice_mesh(mesh.vertices, model.faces, heights);
  REQUIRE(all.size() == heights.size());
  int pieces = 0;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    INFO("height " << heights[i]);
    const auto one = body::slice_mesh(mesh.vertices, model.faces, heights[i]);
    REQUIRE(all[i].size() == one.size());
    for (std::size_t p = 0; p < one.size(); ++p) {
      REQUIRE(all[i][p].points.size() == one[p].points.size());
      for (std::size_t q = 0; q < one[p].points.size(); ++q) {
        CHECK((all[i][p].points[q] - one[p].points[q]).norm() < 1e-12);
      }
    }
    pieces += static_cast<int>(one.size());
  }
  CHECK(pieces > 20);         // the body was cut (torso, arms, legs)
  CHECK(all.back().empty());  // above the head
}

namespace {

// Every point a pass over all faces cuts with the plane (a corner on the plane counts as
// above; with a finite radius only faces with a corner within it of the origin), sorted: the
// reference the batched slices must reproduce.
std::vector<Eigen::Vector2d> brute_force_cut(const body::Vertices& vertices,
                                             const body::Faces& faces,
                                             const body::SlicePlane& plane, double radius) {
  auto distance = [&](std::uint32_t i) {
    return (vertices.row(i).cast<double>().transpose() - plane.origin).dot(plane.normal);
  };
  auto near = [&](std::uint32_t i) {
    return (vertices.row(i).cast<double>().transpose() - plane.origin).norm() <= radius;
  };
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const std::uint32_t v[3] = {faces(f, 0), faces(f, 1), faces(f, 2)};
    if (!near(v[0]) && !near(v[1]) && !near(v[2])) continue;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = v[e], b = v[(e + 1) % 3];
      if ((distance(a) >= 0.0) != (distance(b) >= 0.0))
        edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  std::vector<Eigen::Vector2d> points;
  for (const auto& [a, b] : edges) {
    const double t = distance(a) / (distance(a) - distance(b));
    const Eigen::Vector3d pa = vertices.row(a).cast<double>().transpose();
    const Eigen::Vector3d pb = vertices.row(b).cast<double>().transpose();
    const Eigen::Vector3d q = pa + t * (pb - pa) - plane.origin;
    points.emplace_back(q.dot(plane.u), q.dot(plane.v));
  }
  return points;
}

void sort_points(std::vector<Eigen::Vector2d>& points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
}

}  // namespace

TEST_CASE("slices across many planes in one call cut what a pass over every face cuts",
          "[measurements][slice]") {
  const body::Model model = body::load_builtin_model("male", 10);
  Eigen::VectorXf betas(10);
  betas << -2.0f, 1.5f, 2.5f, -0.5f, 1.0f, -3.0f, 0.4f, 2.0f, -1.2f, 0.0f;
  const body::BodyMesh mesh = body::evaluate(model, betas);
  auto joint = [&](const char* name) {
    for (std::size_t j = 0; j < model.joint_names.size(); ++j)
      if (model.joint_names[j] == name) return Eigen::Vector3d(mesh.joints.row(j).cast<double>());
    FAIL("no joint " << name);
    return Eigen::Vector3d();
  };
  const Eigen::Vector3d shoulder = joint("left_shoulder"), elbow = joint("left_elbow");
  const Eigen::Vector3d neck = joint("neck"), head = joint("head");
  std::vector<body::SlicePlane> planes;
  // Levels across the upper arm, some with the bone's direction normalised once more (a normal
  // an ulp or so away: the same group), the neck's, a tilted plane through the belly, and one
  // that misses the body.
  for (const double t : {0.1, 0.3, 0.5, 0.7})
    planes.push_back(body::plane_across(shoulder + t * (elbow - shoulder), elbow - shoulder));
  const Eigen::Vector3d axis = (elbow - shoulder).normalized();
  for (const double t : {0.2, 0.4})
    planes.push_back(body::plane_across(shoulder + t * (elbow - shoulder), axis));
  for (const double t : {0.3, 0.6})
    planes.push_back(body::plane_across(neck + t * (head - neck), head - neck));
  planes.push_back(
      body::plane_across(Eigen::Vector3d(0.0, 1.0, 0.05), Eigen::Vector3d(0.3, 1.0, -0.2)));
  planes.push_back(body::plane_across(Eigen::Vector3d(0.0, 5.0, 0.0), Eigen::Vector3d::UnitY()));
  for (const double radius : {0.25, std::numeric_limits<double>::infinity()}) {
    const auto all = body::slice_mesh(mesh.vertices, model.faces, planes, radius);
    REQUIRE(all.size() == planes.size());
    for (std::size_t k = 0; k < planes.size(); ++k) {
      INFO("plane " << k << ", radius " << radius);
      std::vector<Eigen::Vector2d> got;
      for (const auto& piece : all[k])
        got.insert(got.end(), piece.points.begin(), piece.points.end());
      std::vector<Eigen::Vector2d> want =
          brute_force_cut(mesh.vertices, model.faces, planes[k], radius);
      if (k + 1 < planes.size()) CHECK(want.size() >= 20);  // each but the last cuts the body
      REQUIRE(got.size() == want.size());
      sort_points(got);
      sort_points(want);
      double worst = 0.0;
      for (std::size_t i = 0; i < got.size(); ++i)
        worst = std::max(worst, (got[i] - want[i]).norm());
      CHECK(worst < 1e-12);
    }
  }
}

TEST_CASE("measure: one girth band alone reads the same as all bands", "[measurements][slice]") {
  const body::Model model = body::load_builtin_model("female", 10);
  Eigen::VectorXf betas(10);
  betas << -1.0f, 2.0f, 0.5f, -2.5f, 1.0f, 0.3f, -0.7f, 2.2f, 0.0f, 1.1f;
  const body::BodyMesh mesh = body::evaluate(model, betas);
  const auto all = body::measure(model, mesh);
  REQUIRE(all.chest > 0.5);
  REQUIRE(all.waist > 0.4);
  REQUIRE(all.hips > 0.5);
  const auto chest = body::measure(model, mesh, true, body::kChestBand);
  CHECK(chest.chest == Approx(all.chest).epsilon(1e-12));
  CHECK(chest.waist == 0.0);
  CHECK(chest.hips == 0.0);
  const auto waist = body::measure(model, mesh, true, body::kWaistBand);
  CHECK(waist.waist == Approx(all.waist).epsilon(1e-12));
  CHECK(waist.chest == 0.0);
  const auto hips = body::measure(model, mesh, true, body::kHipsBand);
  CHECK(hips.hips == Approx(all.hips).epsilon(1e-12));
  CHECK(hips.waist == 0.0);  // the hips' band no longer needs the waist's slice
  CHECK(hips.height == Approx(all.height).epsilon(1e-12));
}

TEST_CASE("each measurement's typed example parses, in both units, near an average body",
          "[measurements]") {
  const body::Model model = body::load_builtin_model("neutral", 10);
  const auto mean = body::measure(model, Eigen::VectorXf::Zero(10));
  for (const auto& k : body::measurement_kinds()) {
    INFO(k.name);
    const std::string metric = k.example_metric, imperial = k.example_imperial;
    REQUIRE(metric.rfind("e.g. ", 0) == 0);
    REQUIRE(imperial.rfind("e.g. ", 0) == 0);
    const double m = body::parse_measurement_value(k, metric.substr(5));
    const double i = body::parse_measurement_value(k, imperial.substr(5));
    CHECK(std::abs(m - i) <= 0.05 * m);
    const double at_mean = mean.*k.field;
    CHECK(m >= 0.7 * at_mean);
    CHECK(m <= 1.4 * at_mean);
  }
}

TEST_CASE("a slice across a tilted cylinder is its circle, whatever the tilt",
          "[measurements][slice]") {
  fixtures::Cylinder c;
  c.radius = 0.05;
  c.height = 0.6;
  c.segments = 64;
  c.rings = 31;
  const auto arrays = fixtures::cylinder_model(c);
  const auto model = load_cylinder(c, "tilted");
  body::BodyMesh mesh = body::evaluate(model, Eigen::VectorXf::Zero(2));
  // Tilt the cylinder (axis y) by 50 degrees about z, as an abducted upper arm lies.
  const double a = 50.0 * kPi / 180.0;
  Eigen::Matrix3f r;
  r << static_cast<float>(std::cos(a)), static_cast<float>(-std::sin(a)), 0.0f,
      static_cast<float>(std::sin(a)), static_cast<float>(std::cos(a)), 0.0f, 0.0f, 0.0f, 1.0f;
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    mesh.vertices.row(i) = (r * mesh.vertices.row(i).transpose()).transpose();
  }
  const Eigen::Vector3d axis = (r.cast<double>() * Eigen::Vector3d::UnitY());
  const Eigen::Vector3d centre = r.cast<double>() * Eigen::Vector3d(0.0, c.base_y + 0.3, 0.0);
  const body::SlicePlane plane = body::plane_across(centre, axis);
  CHECK(plane.normal.dot(plane.u) == Approx(0.0).margin(1e-12));
  CHECK(plane.u.dot(plane.v) == Approx(0.0).margin(1e-12));
  CHECK(plane.v.norm() == Approx(1.0));
  const auto pieces = body::slice_mesh(mesh.vertices, model.faces, plane);
  REQUIRE(pieces.size() == 1);
  const auto hull = body::convex_hull(pieces[0].points);
  CHECK(body::hull_contains(hull, Eigen::Vector2d::Zero()));
  // Single-precision vertices: a few micrometres.
  CHECK(body::polygon_perimeter(hull) == Approx(polygon_girth(c.radius, c.segments)).margin(1e-5));
  (void)arrays;
}

TEST_CASE("measure: neck, deltoid, upper-arm, thigh and calf on the built-in models",
          "[measurements]") {
  const auto female = body::measure(body::load_builtin_model("female", 10), Eigen::VectorXf());
  const auto male = body::measure(body::load_builtin_model("male", 10), Eigen::VectorXf());
  for (const auto* m : {&female, &male}) {
    // Adult ranges (ANSUR II 1st-99th percentiles, both sexes, rounded out).
    CHECK(m->neck > 0.28);
    CHECK(m->neck < 0.50);
    CHECK(m->bideltoid > 0.37);
    CHECK(m->bideltoid < 0.62);
    // The deltoids reach out beyond the acromia.
    CHECK(m->bideltoid > m->shoulder_width + 0.04);
    CHECK(m->upper_arm > 0.22);
    CHECK(m->upper_arm < 0.45);
    CHECK(m->thigh > 0.42);
    CHECK(m->thigh < 0.80);
    CHECK(m->thigh > m->calf);
    CHECK(m->calf > 0.27);
    CHECK(m->calf < 0.50);
  }
  // Men: the broader shoulders and the thicker neck and arms.
  CHECK(male.bideltoid > female.bideltoid + 0.02);
  CHECK(male.neck > female.neck);
  CHECK(male.upper_arm > female.upper_arm);
  // Each band alone reads as all bands do.
  const auto model = body::load_builtin_model("neutral", 10);
  const auto mesh = body::evaluate(model, Eigen::VectorXf::Zero(10));
  const auto all = body::measure(model, mesh);
  const auto neck = body::measure(model, mesh, true, body::kNeckBand);
  CHECK(neck.neck == Approx(all.neck).epsilon(1e-12));
  CHECK(neck.thigh == 0.0);
  const auto arm = body::measure(model, mesh, true, body::kArmBand);
  CHECK(arm.bideltoid == Approx(all.bideltoid).epsilon(1e-12));
  CHECK(arm.upper_arm == Approx(all.upper_arm).epsilon(1e-12));
  const auto leg = body::measure(model, mesh, true, body::kLegBand);
  CHECK(leg.thigh == Approx(all.thigh).epsilon(1e-12));
  CHECK(leg.calf == Approx(all.calf).epsilon(1e-12));
  CHECK(leg.chest == 0.0);
}

TEST_CASE("measure: the limb measures are n/a without the joints they need", "[measurements]") {
  fixtures::Cylinder c;
  auto model = load_cylinder(c, "nolimbs");
  model.joint_names.assign(model.joint_names.size(), "joint");
  const auto m = body::measure(model, Eigen::VectorXf());
  CHECK(std::isnan(m.neck));
  CHECK(std::isnan(m.bideltoid));
  CHECK(std::isnan(m.upper_arm));
  CHECK(std::isnan(m.thigh));
  CHECK(std::isnan(m.calf));
}
