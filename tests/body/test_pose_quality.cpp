// The pose benchmark's figures (body/pose_quality.hpp) on fixtures built here: a tessellated
// cylinder "arm" with two bones bent or twisted at its middle joint, a sphere, single triangles.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>

#include "body/pose_quality.hpp"
#include "body/posing.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// A closed cylinder along +x from 0 to `length`, `segments` around, a ring every `length / (rings
// - 1)`, capped by fans to a centre point at each end; faces wound counter-clockwise seen from
// outside.
struct Tube {
  body::Vertices vertices;
  body::Faces faces;
};

Tube tube(int segments, int rings, double radius = 0.05, double length = 0.6) {
  Tube t;
  const int V = segments * rings + 2;
  t.vertices.resize(V, 3);
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * kPi * s / segments;
      t.vertices.row(r * segments + s) << float(length * r / (rings - 1)),
          float(radius * std::cos(a)), float(radius * std::sin(a));
    }
  }
  const int c0 = segments * rings, c1 = c0 + 1;
  t.vertices.row(c0) << 0.0f, 0.0f, 0.0f;
  t.vertices.row(c1) << float(length), 0.0f, 0.0f;
  std::vector<std::uint32_t> f;
  auto tri = [&](int a, int b, int c) {
    f.push_back(std::uint32_t(a));
    f.push_back(std::uint32_t(b));
    f.push_back(std::uint32_t(c));
  };
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      // Around the ring, then along +x: (a -> b) x (a -> c) points outward.
      tri(a, b, c);
      tri(b, d, c);
    }
  }
  const int last = (rings - 1) * segments;
  for (int s = 0; s < segments; ++s) {
    tri(c0, (s + 1) % segments, s);  // seen from -x
    tri(c1, last + s, last + (s + 1) % segments);
  }
  t.faces = Eigen::Map<const body::Faces>(f.data(), Eigen::Index(f.size() / 3), 3);
  return t;
}

// A two-bone arm on the tube: joint 0 at x = 0 (root), joint 1 (the "elbow") at x = 0.3, joint
// 2 at the end. `blend` is the half width of the weight blend around the elbow (0: a rigid
// split).
struct Arm {
  body::Model model;
  body::Vertices joints;
};

Arm arm(double blend, int segments = 24, int rings = 61) {
  Arm a;
  const Tube t = tube(segments, rings);
  body::Model& m = a.model;
  m.name = "arm";
  m.v_template = t.vertices;
  m.faces = t.faces;
  m.parents = {-1, 0, 1};
  m.joint_names = {"upper", "elbow", "end"};
  m.j_regressor = Eigen::MatrixXf::Zero(3, t.vertices.rows());
  m.weights = Eigen::MatrixXf::Zero(t.vertices.rows(), 3);
  for (Eigen::Index v = 0; v < t.vertices.rows(); ++v) {
    const double x = t.vertices(v, 0);
    double w1;
    if (blend <= 0.0) {
      w1 = x < 0.3 - 1e-6 ? 0.0 : 1.0;
    } else {
      const double u = std::clamp((x - (0.3 - blend)) / (2.0 * blend), 0.0, 1.0);
      w1 = u * u * (3.0 - 2.0 * u);
    }
    m.weights(v, 0) = float(1.0 - w1);
    m.weights(v, 1) = float(w1);
  }
  a.joints.resize(3, 3);
  a.joints << 0.0f, 0.0f, 0.0f, 0.3f, 0.0f, 0.0f, 0.6f, 0.0f, 0.0f;
  return a;
}

struct Posed {
  body::Vertices vertices, joints;
};

Posed pose_elbow(const Arm& a, const Eigen::Matrix3f& elbow) {
  body::Rotations local(3, Eigen::Matrix3f::Identity());
  local[1] = elbow;
  const body::Skinning skin(a.model, local);
  return {skin.vertices(a.model.v_template, a.joints), skin.joints(a.joints)};
}

Eigen::Matrix3f about_z(double degrees) {
  return Eigen::AngleAxisf(float(degrees * kPi / 180.0), Eigen::Vector3f::UnitZ())
      .toRotationMatrix();
}

const body::JointRegion kElbowRegion{1, 0.15};

body::PoseFigures figures(const Arm& a, const Posed& p) {
  const body::RestAndPosed mesh{a.model.v_template, p.vertices, a.joints, p.joints, a.model.faces};
  return body::measure_pose(mesh, a.model.weights, a.model.parents, {kElbowRegion});
}

Eigen::Vector3d row(const body::Vertices& v, int i) {
  return v.row(i).transpose().cast<double>();
}

// A UV sphere (closed, no two non-adjacent faces touch).
Tube sphere(int stacks, int slices, double radius) {
  Tube t;
  t.vertices.resize((stacks - 1) * slices + 2, 3);
  for (int i = 1; i < stacks; ++i) {
    const double th = kPi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double ph = 2.0 * kPi * j / slices;
      t.vertices.row((i - 1) * slices + j) << float(radius * std::sin(th) * std::cos(ph)),
          float(radius * std::cos(th)), float(radius * std::sin(th) * std::sin(ph));
    }
  }
  const int top = (stacks - 1) * slices, bottom = top + 1;
  t.vertices.row(top) << 0.0f, float(radius), 0.0f;
  t.vertices.row(bottom) << 0.0f, float(-radius), 0.0f;
  std::vector<std::uint32_t> f;
  auto tri = [&](int a, int b, int c) {
    f.insert(f.end(), {std::uint32_t(a), std::uint32_t(b), std::uint32_t(c)});
  };
  for (int j = 0; j < slices; ++j) {
    const int n = (j + 1) % slices;
    tri(top, n, j);
    tri(bottom, (stacks - 2) * slices + j, (stacks - 2) * slices + n);
    for (int i = 0; i + 2 < stacks; ++i) {
      const int a = i * slices + j, b = i * slices + n;
      tri(a, b, a + slices);
      tri(b, b + slices, a + slices);
    }
  }
  t.faces = Eigen::Map<const body::Faces>(f.data(), Eigen::Index(f.size() / 3), 3);
  return t;
}

// Reference for triangles_intersect, by another route: two triangles in general position
// intersect iff an edge of one pierces the other (segment against triangle by barycentric
// coordinates of the crossing point).
bool segment_hits_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           const Eigen::Vector3d& r) {
  const Eigen::Vector3d n = (q - p).cross(r - p);
  const double da = n.dot(a - p), db = n.dot(b - p);
  if ((da > 0 && db > 0) || (da < 0 && db < 0) || da == db) return false;
  const Eigen::Vector3d x = a + (b - a) * (da / (da - db));
  const double u = n.dot((q - p).cross(x - p)), v = n.dot((r - q).cross(x - q)),
               w = n.dot((p - r).cross(x - r));
  return (u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0);
}

bool reference_intersect(const std::array<Eigen::Vector3d, 6>& t) {
  for (int e = 0; e < 3; ++e) {
    if (segment_hits_triangle(t[e], t[(e + 1) % 3], t[3], t[4], t[5])) return true;
    if (segment_hits_triangle(t[3 + e], t[3 + (e + 1) % 3], t[0], t[1], t[2])) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("pose quality: the cone volume of a closed tube is its enclosed volume",
          "[pose-quality]") {
  const Tube t = tube(24, 61);
  std::vector<int> all(static_cast<std::size_t>(t.faces.rows()));
  for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
  // A regular 24-gon of radius 0.05 swept over 0.6 m; wound outward, so positive, from any apex.
  const double expected = 0.5 * 24 * 0.05 * 0.05 * std::sin(2 * kPi / 24) * 0.6;
  CHECK(body::cone_volume(t.vertices, t.faces, all, {0.3, 0.0, 0.0}) ==
        Approx(expected).epsilon(1e-5));
  CHECK(body::cone_volume(t.vertices, t.faces, all, {-1.0, 2.0, 0.5}) ==
        Approx(expected).epsilon(1e-5));
}

TEST_CASE("pose quality: the region is the skin of the joint's bones near the joint",
          "[pose-quality]") {
  const Arm a = arm(0.05);
  const auto bones = body::dominant_bones(a.model.faces, a.model.weights);
  const auto region = body::joint_region(a.model.v_template, a.model.faces, bones, a.model.parents,
                                         a.joints, kElbowRegion);
  REQUIRE(!region.empty());
  for (int f : region) {
    for (int k = 0; k < 3; ++k) {
      const float x = a.model.v_template(a.model.faces(f, k), 0);
      CHECK(std::abs(x - 0.3f) < 0.16f);
    }
  }
  // Skin of both bones: the upper arm's (bone 0, the elbow's parent) and the forearm's.
  int upper = 0, fore = 0;
  for (int f : region) ++(bones[static_cast<std::size_t>(f)] == 0 ? upper : fore);
  CHECK(upper > 100);
  CHECK(fore > 100);
  // Nothing of the far end's caps.
  CHECK(region.size() < static_cast<std::size_t>(a.model.faces.rows()) / 2);
  // Only the joint itself, its parent or its child count: a region at the root with a bone
  // set that excludes joint 1 would hold no face of bone 1.
  const auto root =
      body::joint_region(a.model.v_template, a.model.faces, std::vector<int>(bones.size(), 2),
                         a.model.parents, a.joints, {0, 0.15});
  CHECK(root.empty());
}

TEST_CASE("pose quality: a rigid motion about the joint changes neither volume nor folds",
          "[pose-quality]") {
  const Arm a = arm(0.08);
  const Eigen::Matrix3f r =
      Eigen::AngleAxisf(1.1f, Eigen::Vector3f(0.3f, -0.5f, 0.8f).normalized()).toRotationMatrix();
  const Eigen::RowVector3f c = a.joints.row(1), shift(0.4f, -0.2f, 1.0f);
  Posed p{a.model.v_template, a.joints};
  for (Eigen::Index i = 0; i < p.vertices.rows(); ++i) {
    p.vertices.row(i) = (r * (p.vertices.row(i) - c).transpose()).transpose() + c + shift;
  }
  for (Eigen::Index j = 0; j < p.joints.rows(); ++j) {
    p.joints.row(j) = (r * (p.joints.row(j) - c).transpose()).transpose() + c + shift;
  }
  const auto f = figures(a, p);
  CHECK(f.region_faces > 0);
  CHECK(f.volume_change_percent == Approx(0.0).margin(1e-3));
  CHECK(f.sharpest_fold_degrees == Approx(0.0).margin(0.05));
  CHECK(f.intersections.pairs == 0);
}

TEST_CASE("pose quality: growing the region about its joint changes its volume by the cube",
          "[pose-quality]") {
  const Arm a = arm(0.08);
  Posed p{a.model.v_template, a.joints};
  const Eigen::RowVector3f c = a.joints.row(1);
  for (Eigen::Index i = 0; i < p.vertices.rows(); ++i) {
    p.vertices.row(i) = c + 1.1f * (p.vertices.row(i) - c);
  }
  const auto f = figures(a, p);
  CHECK(f.volume_change_percent == Approx(33.1).margin(0.01));
  CHECK(f.sharpest_fold_degrees == Approx(0.0).margin(0.05));  // similar shapes keep angles
}

TEST_CASE("pose quality: a rigid split folds sharply, smooth weights fold less", "[pose-quality]") {
  const auto sharp = figures(arm(0.0), pose_elbow(arm(0.0), about_z(90)));
  const auto smooth = figures(arm(0.1), pose_elbow(arm(0.1), about_z(90)));
  INFO("sharp fold " << sharp.sharpest_fold_degrees << ", smooth fold "
                     << smooth.sharpest_fold_degrees);
  const auto wide = figures(arm(0.2), pose_elbow(arm(0.2), about_z(90)));
  INFO("wide blend fold " << wide.sharpest_fold_degrees);
  // The split folds the band at the joint over (~180 degrees); a blend over +-10 cm still
  // buckles the inner side of a right angle (~60), one over +-20 cm bends it smoothly (~15).
  CHECK(sharp.sharpest_fold_degrees > 120.0);
  CHECK(smooth.sharpest_fold_degrees < 0.5 * sharp.sharpest_fold_degrees);
  CHECK(wide.sharpest_fold_degrees < 0.5 * smooth.sharpest_fold_degrees);
  CHECK(wide.sharpest_fold_degrees < 30.0);
  // The rest pose itself: nothing changes.
  const Arm a = arm(0.1);
  const auto rest = figures(a, pose_elbow(a, Eigen::Matrix3f::Identity()));
  CHECK(rest.volume_change_percent == Approx(0.0).margin(1e-4));
  CHECK(rest.sharpest_fold_degrees == Approx(0.0).margin(1e-4));
}

TEST_CASE("pose quality: linear blend skinning loses volume in a twist (candy wrapper)",
          "[pose-quality]") {
  const Arm a = arm(0.1);
  const Eigen::Matrix3f twist =
      Eigen::AngleAxisf(float(150.0 * kPi / 180.0), Eigen::Vector3f::UnitX()).toRotationMatrix();
  const auto f = figures(a, pose_elbow(a, twist));
  INFO("volume change " << f.volume_change_percent);
  // At the middle of the blend the ring is averaged between its rest and its turned self: its
  // radius shrinks to cos(75 deg) = 0.26 there.
  CHECK(f.volume_change_percent < -10.0);
  CHECK(f.volume_change_percent > -100.0);
}

TEST_CASE("pose quality: Moller's triangle test on known cases", "[pose-quality]") {
  using V = Eigen::Vector3d;
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // A triangle standing through the first one's interior.
  CHECK(body::triangles_intersect(a, b, c, V(0.2, 0.2, -1), V(0.3, 0.2, 1), V(0.2, 0.3, 1)));
  // The same, moved beside it.
  CHECK_FALSE(body::triangles_intersect(a, b, c, V(1.2, 1.2, -1), V(1.3, 1.2, 1), V(1.2, 1.3, 1)));
  // Parallel planes.
  CHECK_FALSE(body::triangles_intersect(a, b, c, V(0, 0, 0.1), V(1, 0, 0.1), V(0, 1, 0.1)));
  // Crossing the plane but beside the triangle (the planes' line misses it).
  CHECK_FALSE(body::triangles_intersect(a, b, c, V(2, -1, -1), V(2, 3, -1), V(2, 1, 1)));
  // Both cross the other's plane, yet their intervals on the common line do not overlap.
  CHECK_FALSE(
      body::triangles_intersect(a, b, c, V(0.8, 0.8, -1), V(0.9, 0.9, 1), V(2.0, 0.1, 0.0)));
  // Coplanar: overlapping, one inside the other, disjoint.
  CHECK(body::triangles_intersect(a, b, c, V(0.5, 0.5, 0), V(1.5, 0.5, 0), V(0.5, 1.5, 0)));
  CHECK(body::triangles_intersect(a, b, c, V(0.1, 0.1, 0), V(0.2, 0.1, 0), V(0.1, 0.2, 0)));
  CHECK_FALSE(body::triangles_intersect(a, b, c, V(2, 2, 0), V(3, 2, 0), V(2, 3, 0)));
  // Touching at a point counts.
  CHECK(body::triangles_intersect(a, b, c, V(0.25, 0.25, 0), V(0.25, 0.0, 1), V(0.5, 0.25, 1)));
  // Degenerate triangles never intersect.
  CHECK_FALSE(body::triangles_intersect(a, b, c, V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.2, 0.2, 1)));
}

TEST_CASE("pose quality: Moller's test agrees with an edge-piercing test on random triangles",
          "[pose-quality]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    std::array<Eigen::Vector3d, 6> t;
    for (int k = 0; k < 6; ++k) t[k] = Eigen::Vector3d(u(rng), u(rng), u(rng));
    // Small second triangles near the first make both outcomes common.
    for (int k = 3; k < 6; ++k) t[k] = t[0] + 0.6 * t[k];
    const bool expected = reference_intersect(t);
    INFO("trial " << trial);
    REQUIRE(body::triangles_intersect(t[0], t[1], t[2], t[3], t[4], t[5]) == expected);
    REQUIRE(body::triangles_intersect(t[3], t[4], t[5], t[0], t[1], t[2]) == expected);
    ++(expected ? hits : misses);
  }
  CHECK(hits > 500);
  CHECK(misses > 500);
}

TEST_CASE("pose quality: the grid finds a known crossing pair and none on clean closed meshes",
          "[pose-quality]") {
  CHECK(body::intersecting_face_pairs(tube(24, 61).vertices, tube(24, 61).faces).empty());
  const Tube s = sphere(24, 32, 0.3);
  CHECK(body::intersecting_face_pairs(s.vertices, s.faces).empty());

  // The sphere plus a triangle through its surface: it crosses exactly the faces around the
  // point where it pierces; a second, far triangle crosses nothing.
  Tube m = s;
  const Eigen::Index V = m.vertices.rows(), F = m.faces.rows();
  m.vertices.conservativeResize(V + 6, 3);
  m.vertices.row(V) << 0.09f, 0.2f, 0.001f;
  m.vertices.row(V + 1) << 0.11f, 0.2f, 0.001f;
  m.vertices.row(V + 2) << 0.1f, 0.4f, -0.001f;
  m.vertices.row(V + 3) << 5.0f, 5.0f, 5.0f;
  m.vertices.row(V + 4) << 5.1f, 5.0f, 5.0f;
  m.vertices.row(V + 5) << 5.0f, 5.1f, 5.0f;
  m.faces.conservativeResize(F + 2, 3);
  m.faces.row(F) << std::uint32_t(V), std::uint32_t(V + 1), std::uint32_t(V + 2);
  m.faces.row(F + 1) << std::uint32_t(V + 3), std::uint32_t(V + 4), std::uint32_t(V + 5);
  const auto pairs = body::intersecting_face_pairs(m.vertices, m.faces);
  REQUIRE(!pairs.empty());
  for (const auto& [f, g] : pairs) {
    CHECK(g == int(F));  // every pair is the piercing triangle with a sphere face
    CHECK(f < int(F));
  }
  // Brute force over all faces gives the same pairs.
  std::vector<std::pair<int, int>> brute;
  for (int f = 0; f < int(m.faces.rows()); ++f) {
    const int g = int(F);
    if (f == g) continue;
    if (body::triangles_intersect(row(m.vertices, m.faces(f, 0)), row(m.vertices, m.faces(f, 1)),
                                  row(m.vertices, m.faces(f, 2)), row(m.vertices, m.faces(g, 0)),
                                  row(m.vertices, m.faces(g, 1)), row(m.vertices, m.faces(g, 2)))) {
      brute.emplace_back(std::min(f, g), std::max(f, g));
    }
  }
  std::sort(brute.begin(), brute.end());
  CHECK(pairs == brute);

  // Counted as new against a rest where the triangle sat outside the sphere, and exempt when
  // both faces are marked.
  Tube rest = m;
  for (int k = 0; k < 3; ++k) rest.vertices(V + k, 1) += 1.0f;
  CHECK(body::new_self_intersections(rest.vertices, m.vertices, m.faces).pairs ==
        int(pairs.size()));
  CHECK(body::new_self_intersections(m.vertices, m.vertices, m.faces).pairs == 0);
  const auto exempt = body::new_self_intersections(
      rest.vertices, m.vertices, m.faces, std::vector<char>(std::size_t(m.faces.rows()), 1));
  CHECK(exempt.pairs == 0);
  CHECK(exempt.exempt_pairs == int(pairs.size()));
}

TEST_CASE("pose quality: a sharply bent arm intersects itself, a smoothly bent one less",
          "[pose-quality]") {
  const Arm split = arm(0.0);
  const Posed bent = pose_elbow(split, about_z(150));
  const auto sharp =
      body::new_self_intersections(split.model.v_template, bent.vertices, split.model.faces);
  CHECK(sharp.pairs > 10);
  const Arm smooth = arm(0.1);
  const auto mild = body::new_self_intersections(
      smooth.model.v_template, pose_elbow(smooth, about_z(45)).vertices, smooth.model.faces);
  CHECK(mild.pairs == 0);
}

TEST_CASE("pose quality: the intersection grid takes seconds on ~20k faces", "[pose-quality]") {
  const Tube t = tube(100, 101, 0.05, 1.0);  // 20,200 faces
  REQUIRE(t.faces.rows() > 20000);
  const auto start = std::chrono::steady_clock::now();
  CHECK(body::intersecting_face_pairs(t.vertices, t.faces).empty());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A test of all pairs would take minutes; the grid takes a fraction of a second.
  CHECK(seconds < 5.0);
}
