// The default body models (female, male, neutral): the generator reproduces the committed
// assets, the template is a closed manifold, the rig is sane, every one of the first 10
// components is visible, and bodies across the +-3 box stay plausible.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "default_model/default_model.hpp"
#include "model_checks.hpp"

#ifdef SG_HAVE_BODY_LIBRARY
#include "body/body_model.hpp"
#include "body/model_loader.hpp"
#include "body/npz_reader.hpp"
#include "body/pose_benchmark.hpp"
#include "body/survey_comparison.hpp"
#include "body/survey_fit.hpp"
#include "default_model/population.hpp"
#endif

using default_model::GeneratedModel;
namespace mc = model_checks;

namespace {

// ctest runs the cases tagged [generated] in one process, which generates the three models
// once (about a minute); every other case is its own process (tests/model/CMakeLists.txt). An
// untagged case that read them would generate them again in its own process, so it fails here
// instead, naming the tag it lacks.
void require_generated_tag() {
  const std::string current = Catch::getResultCapture().getCurrentTestName();
  for (const Catch::TestCase& t : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
    if (t.name != current) continue;
    if (std::find(t.lcaseTags.begin(), t.lcaseTags.end(), "generated") == t.lcaseTags.end()) {
      FAIL("'" << current << "' reads the generated models: tag it [generated]");
    }
    return;
  }
}

const std::vector<GeneratedModel>& all_generated() {
  require_generated_tag();
  static const std::vector<GeneratedModel> models = default_model::generate_default_models();
  return models;
}

const GeneratedModel& generated(const std::string& name = "neutral") {
  for (const GeneratedModel& m : all_generated())
    if (m.name == name) return m;
  throw std::runtime_error("no generated model " + name);
}

std::string asset_path(const std::string& name) {
  return std::string(SG_ASSET_DIR) + "/body_" + name + ".npz";
}

constexpr double kDensity = 985.0;  // kg/m^3, as body::kBodyDensity

mc::Tris faces_of(const GeneratedModel& m) {
  mc::Tris t(m.faces.rows());
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    for (int a = 0; a < 3; ++a) t[f][a] = static_cast<int>(m.faces(f, a));
  return t;
}

mc::Points shape(const GeneratedModel& m, const Eigen::VectorXf& betas) {
  const Eigen::Index V = m.v_template.rows();
  const Eigen::VectorXf offsets = m.shapedirs.leftCols(betas.size()) * betas;
  mc::Points p(V);
  for (Eigen::Index v = 0; v < V; ++v)
    for (int a = 0; a < 3; ++a) p[v][a] = double(m.v_template(v, a)) + double(offsets[3 * v + a]);
  return p;
}

// `count` uniform random points of [-3, 3]^10 (seeded, the same on every platform).
void add_uniform_betas(std::vector<Eigen::VectorXf>& out, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXf b(10);
    for (int k = 0; k < 10; ++k)
      b[k] = float(-3.0 + 6.0 * double(rng() >> 11) / 9007199254740992.0);
    out.push_back(b);
  }
}

// The betas the plausibility test covers: each of the first 10 components at -3 and +3, and
// 30 uniform random points of [-3, 3]^10 (fixed seed).
std::vector<Eigen::VectorXf> test_betas() {
  std::vector<Eigen::VectorXf> out;
  for (int k = 0; k < 10; ++k)
    for (float s : {-3.0f, 3.0f}) {
      Eigen::VectorXf b = Eigen::VectorXf::Zero(10);
      b[k] = s;
      out.push_back(b);
    }
  add_uniform_betas(out, 30, 12345);
  return out;
}

// Body regions by each vertex's dominant skinning joint; a face belongs to a region when all
// three of its vertices do.
enum Region { kTorso, kLeftArm, kRightArm, kLeftLeg, kRightLeg };
Region region_of_joint(int j) {
  // SMPL-X's order: the fingers of the left hand are joints 25..39, the right hand's 40..54.
  if (j >= 25) return j < 40 ? kLeftArm : kRightArm;
  switch (j) {
    case 16:
    case 18:
    case 20:
      return kLeftArm;
    case 17:
    case 19:
    case 21:
      return kRightArm;
    case 1:
    case 4:
    case 7:
    case 10:
      return kLeftLeg;
    case 2:
    case 5:
    case 8:
    case 11:
      return kRightLeg;
    default:
      return kTorso;
  }
}

std::array<std::vector<int>, 5> face_regions(const GeneratedModel& m, const mc::Tris& faces) {
  std::vector<int> vr(m.weights.rows());
  for (Eigen::Index v = 0; v < m.weights.rows(); ++v) {
    Eigen::Index j;
    m.weights.row(v).maxCoeff(&j);
    vr[v] = region_of_joint(static_cast<int>(j));
  }
  std::array<std::vector<int>, 5> out;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const int r = vr[faces[f][0]];
    if (vr[faces[f][1]] == r && vr[faces[f][2]] == r) out[r].push_back(f);
  }
  return out;
}

}  // namespace

#ifdef SG_HAVE_BODY_LIBRARY
// Floating-point results differ in their last bits between CPUs (libm and vector code paths),
// so the regenerated model is compared with the committed one array by array within a
// tolerance, never byte for byte. Only the largest difference is reported, never the arrays.
TEST_CASE("the generator reproduces assets/body_{female,male,neutral}.npz within 1e-5",
          "[model][generated]") {
  REQUIRE(all_generated().size() == 3);
  for (const GeneratedModel& m : all_generated()) {
    INFO("model " << m.name);
    // 4.8 MB: shapedirs 2.3 MB (18 components rounded to a micrometre), posedirs 1.3 MB
    // (limbs, shoulders, hips, head and fingers), the rest under 1.2 MB. Under 5 MB (10^6 bytes)
    // per file, the budget the embedded models were given; it keeps them from growing unnoticed.
    CHECK(m.npz.size() < 5000000u);
    const body::NpzArchive committed = body::NpzArchive::open_file(asset_path(m.name));
    const body::NpzArchive regenerated =
        body::NpzArchive::open_memory(m.npz.data(), m.npz.size(), "regenerated default model");
    const std::vector<std::string> names = committed.names();
    CHECK(names == regenerated.names());  // a handful of short strings
    for (const std::string& name : names) {
      if (!regenerated.contains(name)) continue;
      INFO("array '" << name << "'");
      const body::NpyArray a = committed.read(name);
      const body::NpyArray b = regenerated.read(name);
      CHECK(a.header.descr == b.header.descr);
      CHECK(a.header.shape_string() == b.header.shape_string());
      if (a.header.shape != b.header.shape) continue;
      if (a.header.is_numeric()) {
        const std::vector<double> va = a.to_double();
        const std::vector<double> vb = b.to_double();
        double largest = 0;
        std::size_t where = 0;
        for (std::size_t i = 0; i < va.size(); ++i) {
          const double d = std::abs(va[i] - vb[i]);
          if (!(d <= largest)) {  // also catches NaN
            largest = d;
            where = i;
          }
        }
        INFO("largest difference " << largest << " at element " << where << " of " << va.size());
        // Lengths are metres, so 1e-5 is a hundredth of a millimetre; integer arrays (faces,
        // kintree) must match exactly, which any difference of 1 or more fails.
        CHECK(largest <= 1e-5);
      } else {
        const std::vector<std::string> sa = a.to_strings();
        const std::vector<std::string> sb = b.to_strings();
        std::size_t differing = 0;
        for (std::size_t i = 0; i < sa.size(); ++i) differing += sa[i] != sb[i] ? 1 : 0;
        CHECK(differing == 0);
      }
    }
  }
}
#endif

TEST_CASE("the template is a closed, consistently wound manifold of 8k-20k vertices",
          "[model][generated]") {
  const GeneratedModel& m = generated();
  const mc::Tris faces = faces_of(m);
  const mc::Topology t = mc::topology(static_cast<int>(m.v_template.rows()), faces);
  CHECK(t.vertices >= 8000);
  CHECK(t.vertices <= 20000);
  CHECK(t.non_manifold_edges == 0);
  CHECK(t.inconsistent_edges == 0);
  CHECK(t.non_manifold_vertices == 0);
  CHECK(t.unused_vertices == 0);
  CHECK(t.euler() == 2);  // one closed surface of genus 0
  const mc::Points mean = shape(m, Eigen::VectorXf::Zero(0));
  CHECK(mc::signed_volume(mean, faces) > 0.04);  // m^3, outward winding and adult size
  CHECK(mc::stature(mean) == Approx(1.70).margin(0.03));
  int lowest = 0;
  for (std::size_t v = 0; v < mean.size(); ++v)
    if (mean[v].y() < mean[lowest].y()) lowest = static_cast<int>(v);
  CHECK(std::abs(mean[lowest].y()) < 0.01);  // soles on the ground
}

TEST_CASE(
    "the rig: SMPL-X's 55 joints, convex and fitted regressor rows, normalised sparse weights",
    "[model][generated]") {
  const GeneratedModel& m = generated();
  const Eigen::Index V = m.v_template.rows();
  REQUIRE(m.j_regressor.rows() == 55);
  REQUIRE(m.j_regressor.cols() == V);
  REQUIRE(m.weights.rows() == V);
  REQUIRE(m.weights.cols() == 55);
  for (int j = 0; j < 55; ++j) {
    INFO("joint " << j);
    CHECK(m.j_regressor.row(j).sum() == Approx(1.0).margin(1e-4));
    // The shoulders' rows are least squares fitted to the generator's placed joints
    // (default_model.cpp, fit_shoulder_rows): small signed weights on the skin within 10 cm
    // of the joint. The others are convex.
    if (j == 16 || j == 17) {
      CHECK(m.j_regressor.row(j).minCoeff() > -0.1f);
      CHECK(m.j_regressor.row(j).maxCoeff() < 0.1f);
      const Eigen::RowVector3f joint = m.j_regressor.row(j) * m.v_template;
      for (Eigen::Index v = 0; v < V; ++v)
        if (m.j_regressor(j, v) != 0.0f) REQUIRE((m.v_template.row(v) - joint).norm() < 0.11f);
    } else {
      CHECK(m.j_regressor.row(j).minCoeff() >= 0.0f);
    }
  }
  CHECK(m.weights.minCoeff() >= 0.0f);
  std::vector<int> dominant(55, 0);
  for (Eigen::Index v = 0; v < V; ++v) {
    REQUIRE(m.weights.row(v).sum() == Approx(1.0).margin(1e-4));
    REQUIRE((m.weights.row(v).array() > 0).count() <= 4);
    Eigen::Index j;
    m.weights.row(v).maxCoeff(&j);
    ++dominant[j];
  }
  CHECK(m.joint_fit_error < 1e-3);
  CHECK(m.vertices_without_visible_bone < V / 100);
  // Every joint moves a part of the body of its own, the finger joints included (the hand
  // bone of the old 24-joint rig folded all five fingers together).
  for (int j = 0; j < 55; ++j) {
    INFO("joint " << j);
    CHECK(dominant[j] >= 5);
  }
  // Joints where a body has them: head above neck above pelvis above knees above ankles, left
  // joints on +x; jaw below and in front of the head joint's level at the face, eyes in front
  // at eye height; each finger runs away from its wrist.
  const auto& J = m.joints;
  CHECK(J(15, 1) > J(12, 1));
  CHECK(J(12, 1) > J(0, 1));
  CHECK(J(0, 1) > J(4, 1));
  CHECK(J(4, 1) > J(7, 1));
  for (int left : {1, 4, 7, 10, 13, 16, 18, 20, 23}) {
    CHECK(J(left, 0) > 0.02f);
    CHECK(J(left + 1, 0) == Approx(-J(left, 0)).margin(1e-3));
  }
  CHECK(std::abs(J(22, 0)) < 1e-3f);
  CHECK(J(22, 2) > J(15, 2));
  for (int eye : {23, 24}) {
    CHECK(J(eye, 1) > J(15, 1) + 0.03f);
    CHECK(J(eye, 2) > J(15, 2) + 0.05f);
  }
  for (int i = 0; i < 15; ++i) {
    INFO("finger joint " << i);
    const int l = 25 + i, r = 40 + i;
    CHECK(J(l, 0) > 0.3f);
    CHECK(J(r, 0) == Approx(-J(l, 0)).margin(1e-3));
    const int parent = i % 3 == 0 ? 20 : l - 1;
    const int grandparent = i % 3 == 0 ? 18 : (i % 3 == 1 ? 20 : l - 2);
    CHECK((J.row(l) - J.row(grandparent)).norm() > (J.row(parent) - J.row(grandparent)).norm());
  }
}

TEST_CASE("the texture layout: charts by body part, in [0, 1]^2, none flipped, low distortion",
          "[model][uv][generated]") {
  const GeneratedModel& m = generated();
  const auto& uv = m.uv;
  REQUIRE(uv.faces.size() == static_cast<std::size_t>(m.faces.rows()));
  // Seams split vertices: more texture vertices than vertices, but not wildly more.
  CHECK(uv.uv.size() > static_cast<std::size_t>(m.v_template.rows()));
  CHECK(uv.uv.size() < static_cast<std::size_t>(1.2 * m.v_template.rows()));
  for (const auto& p : uv.uv) {
    REQUIRE(p.x() >= 0.0);
    REQUIRE(p.x() <= 1.0);
    REQUIRE(p.y() >= 0.0);
    REQUIRE(p.y() <= 1.0);
  }
  // A face's corners are texture vertices of that face's own vertices.
  std::vector<int> vertex_of(uv.uv.size(), -1);
  for (std::size_t f = 0; f < uv.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      int& v = vertex_of[uv.faces[f][c]];
      if (v < 0) v = static_cast<int>(m.faces(f, c));
      REQUIRE(v == static_cast<int>(m.faces(f, c)));
    }
  const default_model::UvDistortion& d = m.uv_distortion;
  std::printf("uv layout: %s\n", d.describe().c_str());
  // Torso front and back, face and back of the head, eyes, arms, hands (back and palm), legs,
  // feet (top and sole): 18 parts.
  CHECK(d.charts >= 18);
  CHECK(d.charts <= 24);
  CHECK(d.flipped_faces == 0);
  CHECK(d.angle_mean_deg < 2.0);
  CHECK(d.area_log2_mean < 0.5);
  CHECK(d.packing > 0.35);
}

TEST_CASE("the shape spaces: 18 components, betas ~ N(0, 1), variance shares",
          "[model][generated]") {
  for (const GeneratedModel& m : all_generated()) {
    INFO("model " << m.name);
    const Eigen::Index K = m.shapedirs.cols();
    REQUIRE(K >= 18);
    REQUIRE(m.variance_share.size() == K);
    CHECK(m.variance_share.sum() <= 1.0001f);
    CHECK(m.variance_share.head(18).sum() > 0.95f);
    // Real populations vary in more than size: the first component must not take it all
    // (the first version of the default model had 0.956).
    std::printf("%s: first component's variance share %.3f\n", m.name.c_str(),
                double(m.variance_share[0]));
    CHECK(m.variance_share[0] < (m.name == "neutral" ? 0.9f : 0.85f));
    // Components 3-10 (the searched ones after the stature and mass axes) largest first,
    // and so are 11-18, which are also orthogonal (survey_pca in tools/default_model/pca.hpp).
    for (Eigen::Index k = 3; k < 10; ++k) CHECK(m.variance_share[k] <= m.variance_share[k - 1]);
    const Eigen::MatrixXd G = m.shapedirs.cast<double>().transpose() * m.shapedirs.cast<double>();
    for (Eigen::Index a = 11; a < K; ++a) {
      CHECK(m.variance_share[a] <= m.variance_share[a - 1]);
      for (Eigen::Index b = 10; b < a; ++b)
        CHECK(std::abs(G(a, b)) < 1e-3 * std::sqrt(G(a, a) * G(b, b)) + 1e-9);
    }
    for (Eigen::Index k = 1; k < K; ++k)
      CHECK(G(k, k) / G(0, 0) == Approx(m.variance_share[k] / m.variance_share[0]).epsilon(1e-3));
    // Population statures: ANSUR II, per sex (neutral: both), 2000 bodies per sex.
    double sum = 0;
    for (double st : m.population_statures) sum += st;
    const double mean_stature = sum / m.population_statures.size();
    CHECK(m.population_statures.size() >= (m.name == "neutral" ? 4000u : 2000u));
    const double expected = m.name == "female" ? 1.63 : m.name == "male" ? 1.76 : 1.70;
    CHECK(mean_stature == Approx(expected).margin(0.025));
  }
}

// A grid cell shows a 1.8 m body in 400 px (1 px ~ 4.5 mm): each of the first 10 components
// must move the surface visibly at +-3 SD.
TEST_CASE("each of the first 10 components moves the surface by >= 8 mm mean, 25 mm max",
          "[model][generated]") {
  for (const GeneratedModel& m : all_generated()) {
    const Eigen::Index V = m.v_template.rows();
    for (int k = 0; k < 10; ++k) {
      double sum = 0, largest = 0;
      for (Eigen::Index v = 0; v < V; ++v) {
        const double d = 3.0 * m.shapedirs.block(3 * v, k, 3, 1).cast<double>().norm();
        sum += d;
        largest = std::max(largest, d);
      }
      INFO("model " << m.name << ", component " << k + 1 << ": mean " << 1000 * sum / V
                    << " mm, max " << 1000 * largest << " mm");
      CHECK(sum / V >= 0.008);
      CHECK(largest >= 0.025);
    }
  }
}

// Size and weight are not one knob (issue 8: "short and heavy" must be reachable): component
// 1 carries all of the searched components' stature, component 2 the mass beyond it. So the
// other nine leave stature alone, component 2 changes mass by >= 15 kg with stature within
// 3 cm, and components 1 at -1.5 and 2 at +3 make a body at least 8 cm shorter and 10 kg
// heavier than the mean (female and male models).
TEST_CASE("component 1 is stature, component 2 mass at that stature", "[model][generated]") {
  for (const GeneratedModel& m : all_generated()) {
    INFO("model " << m.name);
    const mc::Tris faces = faces_of(m);
    const mc::Points mean = shape(m, Eigen::VectorXf::Zero(0));
    const double mass0 = kDensity * mc::signed_volume(mean, faces);
    const double stature0 = mc::stature(mean);
    auto change = [&](std::vector<std::pair<int, float>> at) {
      Eigen::VectorXf b = Eigen::VectorXf::Zero(10);
      for (const auto& [k, value] : at) b[k] = value;
      const mc::Points v = shape(m, b);
      return std::pair<double, double>{kDensity * mc::signed_volume(v, faces) - mass0,
                                       mc::stature(v) - stature0};
    };
    for (int k = 0; k < 10; ++k) {
      for (const float s : {-3.0f, 3.0f}) {
        const auto [dm, dh] = change({{k, s}});
        std::printf("%s component %d at %+.0f: mass %+.1f kg, stature %+.1f cm\n", m.name.c_str(),
                    k + 1, double(s), dm, 100 * dh);
        INFO("component " << k + 1 << " at " << s << ": mass " << dm << " kg, stature " << 100 * dh
                          << " cm");
        if (k == 0) CHECK(std::abs(dh) >= 0.10);
        if (k == 1) {
          CHECK(std::abs(dm) >= 15.0);
          CHECK(std::abs(dh) < 0.03);
        }
        // The linear stature of the other components is zero; what is left is the
        // measured stature's own curvature (its highest vertex can change).
        if (k >= 1) CHECK(std::abs(dh) < 0.01);
      }
    }
    if (m.name == "neutral") continue;  // its component 1 is also the sexes' difference
    const auto [dm, dh] = change({{0, -1.5f}, {1, 3.0f}});
    INFO("short and heavy: mass " << dm << " kg, stature " << 100 * dh << " cm");
    CHECK(dh <= -0.08);
    CHECK(dm >= 10.0);
  }
}

TEST_CASE("bodies at +-3 per component and at random betas in [-3, 3]^10 are plausible",
          "[model][generated]") {
  for (const GeneratedModel& m : all_generated()) {
    INFO("model " << m.name);
    const mc::Tris faces = faces_of(m);
    const mc::Points mean = shape(m, Eigen::VectorXf::Zero(0));
    const auto regions = face_regions(m, faces);
    std::vector<int> torso_and_legs = regions[kTorso];
    torso_and_legs.insert(torso_and_legs.end(), regions[kLeftLeg].begin(), regions[kLeftLeg].end());
    torso_and_legs.insert(torso_and_legs.end(), regions[kRightLeg].begin(),
                          regions[kRightLeg].end());
    REQUIRE(regions[kLeftArm].size() > 500);
    REQUIRE(regions[kLeftLeg].size() > 500);
    double lowest = 10, highest = 0;
    int index = 0, worst_inverted = 0, worst_arm = 0, worst_legs = 0;
    for (const Eigen::VectorXf& betas : test_betas()) {
      const mc::Points v = shape(m, betas);
      INFO("betas " << betas.transpose());
      const double h = mc::stature(v);
      lowest = std::min(lowest, h);
      highest = std::max(highest, h);
      const int inverted = mc::inverted_triangles(mean, v, faces);
      const int left_arm = mc::intersecting_pairs(v, faces, regions[kLeftArm], torso_and_legs);
      const int right_arm = mc::intersecting_pairs(v, faces, regions[kRightArm], torso_and_legs);
      const int legs = mc::intersecting_pairs(v, faces, regions[kLeftLeg], regions[kRightLeg]);
      worst_inverted = std::max(worst_inverted, inverted);
      worst_arm = std::max({worst_arm, left_arm, right_arm});
      worst_legs = std::max(worst_legs, legs);
      if (h < 1.45 || h > 2.05 || inverted || left_arm || right_arm || legs)
        std::printf("%s betas %d: stature %.3f m, %d inverted, arm-torso %d/%d, leg-leg %d\n",
                    m.name.c_str(), index, h, inverted, left_arm, right_arm, legs);
      ++index;
      // Each component alone at -3 and +3 (the first 20) and the seeded random points of
      // [-3, 3]^10: all must hold.
      CHECK(h >= 1.45);
      CHECK(h <= 2.05);
      CHECK(inverted == 0);
      CHECK(left_arm == 0);
      CHECK(right_arm == 0);
      CHECK(legs == 0);
      CHECK(mc::signed_volume(v, faces) > 0.02);
    }
    std::printf(
        "%s: over %d bodies statures %.3f - %.3f m, at most %d inverted triangles, %d "
        "arm-torso and %d leg-leg intersecting pairs\n",
        m.name.c_str(), index, lowest, highest, worst_inverted, worst_arm, worst_legs);
  }
}

TEST_CASE("no male body shows breasts, and the female model's breasts span a range",
          "[model][generated]") {
  // Each of the first 10 components at -3 and +3, and 500 uniform points of the [-3, 3]^10 box.
  std::vector<Eigen::VectorXf> betas = test_betas();
  betas.resize(20);
  add_uniform_betas(betas, 500, 2024);
  // The fold is looked for within 4% of the stature (7 cm) below each level of the chest.
  constexpr double kWindow = 0.04;
  auto projections = [&](const std::string& name) {
    std::vector<double> out;
    for (const Eigen::VectorXf& b : betas)
      out.push_back(mc::breast_projection(shape(generated(name), b), kWindow));
    return out;
  };
  auto mean_body = [&](const std::string& name) {
    return mc::breast_projection(shape(generated(name), Eigen::VectorXf::Zero(0)), kWindow);
  };
  const std::vector<double> men = projections("male");
  const std::vector<double> women = projections("female");
  const auto [men_lo, men_hi] = std::minmax_element(men.begin(), men.end());
  const auto [women_lo, women_hi] = std::minmax_element(women.begin(), women.end());
  INFO("male body with the largest projection: betas "
       << betas[static_cast<std::size_t>(men_hi - men.begin())].transpose());
  std::printf(
      "chest projection over its fold (cm): male %.1f - %.1f (mean body %.1f), female %.1f - "
      "%.1f (mean body %.1f)\n",
      100 * *men_lo, 100 * *men_hi, 100 * mean_body("male"), 100 * *women_lo, 100 * *women_hi,
      100 * mean_body("female"));
  // The average man's pectoral stands about a centimetre over its lower border, the average
  // woman's breast two to three; a bodybuilder's pectoral up to about 4 cm, which is where the
  // male model's corners of the box (big pectorals on a slim waist) end.
  CHECK(mean_body("male") < 0.012);
  CHECK(mean_body("female") > 0.02);
  CHECK(mean_body("female") > 2.0 * mean_body("male"));
  CHECK(*men_hi < 0.04);
  CHECK(*women_hi - *women_lo > 0.03);
}

TEST_CASE("each sex's bodies are measured against their own survey draw",
          "[model][survey][generated]") {
  // The generator's calibration (survey_calibration.hpp): the girths the tool measures on a
  // sample of each population, against the girths each person was drawn with.
  for (const std::string name : {"female", "male"}) {
    const GeneratedModel& m = generated(name);
    REQUIRE(m.calibration_reports.size() == 1);
    const default_model::CalibrationReport& r = m.calibration_reports.front();
    std::printf("%s\n", default_model::describe(r).c_str());
    CHECK(r.female == (name == "female"));
    CHECK(r.sample >= 200);
    CHECK(r.rounds >= 1);
    for (int k = 0; k < default_model::kKnobCount; ++k) {
      INFO(name << " " << default_model::knob_measurement_names()[k]);
      // Before: 7-16% RMS. On this build after: 0.4-2.8% RMS, biases under 1.3%.
      CHECK(r.rms_after[k] < 0.04);
      CHECK(r.rms_after[k] < 0.5 * r.rms_before[k]);
      CHECK(std::abs(r.bias_after[k]) < 0.025);
      // The bands stay soft tissue, not a second body: under 10 cm at a thigh's radius on
      // average and in spread (the shoulders' spread: under 10% of the drawn one). The
      // deltoid's band is narrow, smoothed over the mesh and faded over the acromion, so that
      // its amplitude is far larger than what it moves: a spread of 17 cm there is the
      // survey's bideltoid spread, about 1.5 cm of tissue per side. (The mass's fat layer is
      // in metres of tissue: it spreads about 1.5 cm.)
      CHECK(std::abs(r.knob_mean[k]) < 0.10);
      CHECK(r.knob_sd[k] < (k == default_model::kKnobDeltoid ? 0.20 : 0.10));
    }
  }
  CHECK(generated("neutral").calibration_reports.size() == 2);
}

#ifdef SG_HAVE_BODY_LIBRARY
// fit-survey's check on people drawn from the committed survey statistics (the survey's rows
// are never committed): the measures the generator draws that the tool measures the same way.
TEST_CASE("people drawn from the survey statistics are near bodies of their sex's model",
          "[model][fit]") {
  const std::vector<std::string> names = {"height", "mass",  "chest", "waist", "hips",
                                          "neck",   "thigh", "calf",  "inseam"};
  for (const bool female : {true, false}) {
    using namespace default_model;
    const std::vector<Anthropometry> people = sample_population(female, 24, 77);
    // A survey table in the survey's own units (mm; weightkg in tenths of a kg).
    body::SurveyTable table;
    table.source = female ? "drawn-women" : "drawn-men";
    table.columns = body::survey_columns();
    table.values =
        Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(people.size()),
                                  static_cast<Eigen::Index>(table.columns.size()), std::nan(""));
    const std::vector<std::pair<std::string, std::pair<int, double>>> columns = {
        {"stature", {k_stature, 10.0}},
        {"weightkg", {k_weight, 10.0}},
        {"chestcircumference", {k_chest_circ, 10.0}},
        {"waistcircumference", {k_waist_circ, 10.0}},
        {"buttockcircumference", {k_buttock_circ, 10.0}},
        {"neckcircumference", {k_neck_circ, 10.0}},
        {"thighcircumference", {k_thigh_circ, 10.0}},
        {"calfcircumference", {k_calf_circ, 10.0}},
        {"crotchheight", {k_crotch_height, 10.0}}};
    for (std::size_t p = 0; p < people.size(); ++p)
      for (const auto& [column, source] : columns)
        table.values(static_cast<Eigen::Index>(p), table.column(column)) =
            source.second * people[p].m[static_cast<std::size_t>(source.first)];
    const std::string name = female ? "female" : "male";
    const auto model = std::make_shared<const body::Model>(body::load_model(asset_path(name), 0));
    const body::SurveyFit fit = body::fit_survey(model, {&table}, 24, 5, 2, names);
    for (const auto& r : fit.rows) {
      std::printf("%s: %-7s median %.2f %s, p95 %.2f\n", name.c_str(), r.name.c_str(),
                  r.median_abs_error, r.unit.c_str(), r.p95_abs_error);
      INFO(name << " " << r.name);
      // The goal for all components, 1 cm and 1 kg median: on this build the medians
      // are 0.0-0.4 cm and under 0.1 kg (0.3-2.9 cm and 1.2-1.8 kg before each body was
      // measured against its own draw). These people come from the generator's own
      // statistics; real ones (fit-survey) are farther.
      CHECK(r.median_abs_error <= 1.0);
    }
  }
}

TEST_CASE("the committed assets load through body::load_model like an SMPL file",
          "[model][generated]") {
  for (const GeneratedModel& m : all_generated()) {
    INFO("model " << m.name);
    const body::Model model = body::load_model(asset_path(m.name), 0);
    REQUIRE(model.vertex_count() == m.v_template.rows());
    REQUIRE(model.component_count() == m.shapedirs.cols());
    REQUIRE(model.joint_count() == 55);
    CHECK(model.parents[0] == -1);
    CHECK(model.joint_names[22] == "jaw");
    CHECK(model.parents[22] == 15);
    CHECK(model.joint_names[54] == "right_thumb3");
    CHECK(model.parents[54] == 53);
    CHECK(model.parents[40] == 21);
    CHECK(model.faces.rows() == m.faces.rows());
    Eigen::VectorXf betas = Eigen::VectorXf::Zero(10);
    betas << 1.5f, -2.0f, 0.5f, 3.0f, -1.0f, 0.0f, 2.0f, -3.0f, 1.0f, -0.5f;
    const body::BodyMesh mesh = body::evaluate(model, betas);
    const mc::Points ours = shape(m, betas);
    double err = 0;
    for (std::size_t v = 0; v < ours.size(); ++v)
      err = std::max(err, (mesh.vertices.row(v).cast<double>().transpose() - ours[v]).norm());
    CHECK(err < 1e-5);
    // The built-in model of that name is the same file.
    const body::Model builtin = body::resolve_model(m.name, 0);
    CHECK(builtin.name == m.name);
    CHECK(builtin.vertex_count() == model.vertex_count());
    CHECK((builtin.v_template - model.v_template).cwiseAbs().maxCoeff() == 0.0f);
  }
}

TEST_CASE(
    "the rig bends: smooth folds, and correctives keep the limbs', shoulders', hips', head's and "
    "knuckles' volume",
    "[model][pose]") {
  // The committed male model (its correctives were fitted by the generator) on its mean body.
  body::Model with = body::load_model(asset_path("male"), 3);
  body::load_pose_correctives(with);
  REQUIRE(with.posedirs.cols() == 9 * (with.joint_count() - 1));
  body::Model without = with;
  without.posedirs.resize(0, 0);
  const body::ModelBenchmark a = body::run_pose_benchmark(with, "with", 0);
  const body::ModelBenchmark b = body::run_pose_benchmark(without, "without", 0);
  REQUIRE(a.correctives);
  REQUIRE_FALSE(b.correctives);
  const auto find = [](const body::ModelBenchmark& m, const std::string& name) {
    for (const auto& p : m.poses)
      if (p.pose->name == name) return p;
    FAIL("no pose " << name);
    return m.poses.front();
  };
  // Bone heat weights: folds a skinning artist accepts where the distance weights of the old
  // 24-joint rig folded sharply (64, 91, 180 and 46 degrees there).
  for (const char* pose : {"shoulder-abduct-80", "wrist-flex-60", "hip-flex-90", "head-turn-60"}) {
    INFO(pose);
    CHECK(find(a, pose).fold_worst < 60.0);
  }
  // The limbs' correctives (elbows, knees, ankles) give back much of the volume plain skinning
  // loses.
  for (const char* pose : {"elbow-130", "forearm-twist-90", "knee-130"}) {
    const double w = find(a, pose).volume_worst, wo = find(b, pose).volume_worst;
    INFO(pose << ": " << w << " % with the correctives, " << wo << " % without");
    CHECK(std::abs(w) < std::abs(wo) - 5.0);
  }
  CHECK(std::abs(find(a, "forearm-twist-90").volume_worst) < 12.0);
  // Bent to 130 degrees, the elbows' and knees' flesh is pressed together: the forearm no
  // longer goes through the biceps, nor the calf through the thigh (14 and 9 pairs on this
  // body when written; hundreds with plain skinning, 218 and 420 with the previous correctives).
  for (const char* pose : {"elbow-130", "knee-130"}) {
    const body::PoseResult& w = find(a, pose);
    const body::PoseResult& wo = find(b, pose);
    INFO(pose << ": " << w.intersections_worst << " self-intersecting pairs with the correctives, "
              << wo.intersections_worst << " without");
    CHECK(w.intersections_worst <= 40);
    CHECK(wo.intersections_worst > 100);
  }
  // Raised straight forward, the upper arm's inner skin meets the pectoral: the shoulders'
  // correctives keep it outside the chest (90 pairs on this body with the previous ones).
  {
    const body::PoseResult& w = find(a, "shoulder-flex-90");
    const body::PoseResult& wo = find(b, "shoulder-flex-90");
    INFO("shoulder-flex-90: " << w.intersections_worst
                              << " self-intersecting pairs with the correctives, "
                              << wo.intersections_worst << " without");
    CHECK(w.intersections_worst == 0);
    CHECK(wo.intersections_worst > 100);
  }
  // At the shoulders, hips and head each vertex of the blend zone turns by its share of the
  // rotation: the region keeps its volume where plain skinning collapses it onto the chord,
  // and the raised arm no longer sinks into the shoulder (self-intersections there before).
  for (const char* pose : {"shoulder-abduct-170", "hip-flex-90", "head-turn-60"}) {
    const body::PoseResult& w = find(a, pose);
    const body::PoseResult& wo = find(b, pose);
    INFO(pose << ": " << w.volume_worst << " % with the correctives, " << wo.volume_worst
              << " % without; " << w.intersections_worst << " self-intersections");
    CHECK(std::abs(w.volume_worst) < 8.0);
    CHECK(std::abs(wo.volume_worst) > 15.0);
    CHECK(w.intersections_worst == 0);
  }
  // Every finger joint is there for a fist, and the fingers' correctives keep each knuckle's
  // volume where plain skinning loses a quarter of it (-27 % on the mean bodies before).
  REQUIRE(find(a, "fist").available);
  {
    const body::PoseResult& w = find(a, "fist");
    const body::PoseResult& wo = find(b, "fist");
    INFO("fist: " << w.volume_worst << " % with the correctives, " << wo.volume_worst
                  << " % without");
    CHECK(std::abs(w.volume_worst) < 8.0);
    CHECK(std::abs(wo.volume_worst) > 15.0);
  }
}
TEST_CASE(
    "the head turns 60 degrees within the volume target on every +-3 SD body of components 1-3",
    "[model][pose]") {
  // Posedirs are one set for all bodies, fitted on the mean body: with the head's whole
  // rotation share the neutral model's c1-3 body (a thinner neck than the mean's) gained 8.1 %.
  for (const char* name : {"female", "male", "neutral"}) {
    body::Model model = body::load_model(asset_path(name), 3);
    body::load_pose_correctives(model);
    const body::ModelBenchmark bench =
        body::run_pose_benchmark(model, name, 3, body::PoseTargets{}, {"head-turn-60"});
    bool found = false;
    for (const body::PoseResult& p : bench.poses) {
      if (p.pose->name != "head-turn-60") {
        CHECK_FALSE(p.available);  // only the head turn was asked for
        continue;
      }
      found = true;
      REQUIRE(p.available);
      INFO(name << ": head-turn-60 worst volume change " << p.volume_worst << " %");
      CHECK(std::abs(p.volume_worst) <= 8.0);
      CHECK(p.fold_worst < 60.0);
    }
    CHECK(found);
  }
}
#endif
