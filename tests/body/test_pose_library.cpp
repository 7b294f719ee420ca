// The named test poses (body/pose_library.hpp) on fixture skeletons built here: SMPL's 24 joints
// in an A-pose, and SMPL-X's 55 with hands, each joint a vertex rigidly bound to it, so the
// posed vertices are the posed joints. Also the pose benchmark's report on results made by hand.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "body/joint_names.hpp"
#include "body/pose_benchmark.hpp"
#include "body/pose_library.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

double degrees_between(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const double c = double(a.normalized().dot(b.normalized()));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi;
}

const int kSmplParents[24] = {-1, 0, 0, 0,  1,  2,  3,  4,  5,  6,  7,  8,
                              9,  9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};

// The upper arm's rest direction (left side): down and out at 45 degrees, a little forward,
// and the forearm and hand straight on from it.
const Eigen::Vector3f kArm = Eigen::Vector3f(0.7f, -0.7f, 0.1f).normalized();

struct Skeleton {
  body::Model model;
  body::BodyMesh rest;
};

int index_of(const body::Model& m, const std::string& name) {
  for (std::size_t j = 0; j < m.joint_names.size(); ++j) {
    if (m.joint_names[j] == name) return static_cast<int>(j);
  }
  FAIL("no joint " << name);
  return -1;
}

// Every joint a vertex bound to it alone; no faces (the pose library needs none).
Skeleton make_skeleton(const std::vector<std::string>& names, const std::vector<int>& parents,
                       const body::Vertices& joints) {
  Skeleton s;
  const int J = static_cast<int>(names.size());
  s.model.name = "skeleton";
  s.model.joint_names = names;
  s.model.parents = parents;
  s.model.v_template = joints;
  s.model.faces.resize(0, 3);
  s.model.j_regressor = Eigen::MatrixXf::Identity(J, J);
  s.model.weights = Eigen::MatrixXf::Identity(J, J);
  s.model.shapedirs = Eigen::MatrixXf::Zero(3 * J, 0);
  s.rest.vertices = joints;
  s.rest.joints = joints;
  s.rest.normals = body::Vertices::Zero(J, 3);
  return s;
}

// SMPL's 24 joints in an A-pose, metres, y up, facing +z, left on +x (mirrored right side).
body::Vertices smpl_joints() {
  body::Vertices j(24, 3);
  auto set = [&](int i, float x, float y, float z) { j.row(i) << x, y, z; };
  set(0, 0, 0.93f, 0);  // pelvis
  set(3, 0, 1.03f, -0.01f);
  set(6, 0, 1.15f, -0.01f);
  set(9, 0, 1.26f, -0.01f);
  set(12, 0, 1.44f, -0.02f);  // neck
  set(15, 0, 1.53f, 0);       // head
  for (int side = 0; side < 2; ++side) {
    const float s = side == 0 ? 1.0f : -1.0f;
    const Eigen::Vector3f arm(s * kArm.x(), kArm.y(), kArm.z());
    set(1 + side, s * 0.09f, 0.85f, 0);        // hips
    set(4 + side, s * 0.10f, 0.48f, 0.01f);    // knees
    set(7 + side, s * 0.11f, 0.08f, -0.02f);   // ankles
    set(10 + side, s * 0.12f, 0.02f, 0.10f);   // feet
    set(13 + side, s * 0.05f, 1.37f, -0.02f);  // collars
    const Eigen::Vector3f shoulder(s * 0.17f, 1.37f, -0.03f);
    j.row(16 + side) = shoulder.transpose();
    j.row(18 + side) = (shoulder + 0.27f * arm).transpose();  // elbows
    j.row(20 + side) = (shoulder + 0.52f * arm).transpose();  // wrists
    j.row(22 + side) = (shoulder + 0.60f * arm).transpose();  // hand ends
  }
  return j;
}

Skeleton smpl_skeleton() {
  return make_skeleton(body::smpl_joint_names(),
                       std::vector<int>(std::begin(kSmplParents), std::end(kSmplParents)),
                       smpl_joints());
}

// The palm's outward normal of the fixture's left hand: down and in, perpendicular to the arm
// (a relaxed hand, palm toward the thigh); the right hand mirrors it.
Eigen::Vector3f left_palm() {
  const Eigen::Vector3f in(-1.0f, 0.0f, 0.0f);
  return (in - in.dot(kArm) * kArm).normalized();
}

// SMPL-X's 55 joints: the 22 body joints above, jaw and eyes, and on each hand four fingers
// fanned across the knuckles and a thumb on the radial side.
Skeleton smplx_skeleton() {
  const auto* names = body::builtin_joint_names(55);
  REQUIRE(names);
  const body::Vertices body24 = smpl_joints();
  body::Vertices j(55, 3);
  j.topRows(22) = body24.topRows(22);
  std::vector<int> parents(kSmplParents, kSmplParents + 22);
  j.row(22) << 0.0f, 1.50f, 0.05f;   // jaw
  j.row(23) << 0.03f, 1.57f, 0.08f;  // eyes
  j.row(24) << -0.03f, 1.57f, 0.08f;
  parents.insert(parents.end(), {15, 15, 15});
  for (int side = 0; side < 2; ++side) {
    const float s = side == 0 ? 1.0f : -1.0f;
    auto mirror = [s](Eigen::Vector3f v) {
      v.x() *= s;
      return v;
    };
    const Eigen::Vector3f h = mirror(kArm);
    // Left hand: palm = h x radial, so radial = palm x h (toward the thumb); mirrored on the
    // right side.
    const Eigen::Vector3f radial = mirror(left_palm().cross(kArm));
    const int wrist = 20 + side;
    const Eigen::Vector3f w = j.row(wrist).transpose();
    // builtin order per hand: index, middle, pinky, ring, thumb; three joints each.
    const float across[4] = {0.03f, 0.01f, -0.03f, -0.01f};
    const float reach[4] = {0.090f, 0.095f, 0.080f, 0.090f};
    const int base = 25 + 15 * side;
    for (int f = 0; f < 4; ++f) {
      Eigen::Vector3f p = w + reach[f] * h + across[f] * radial;
      for (int k = 0; k < 3; ++k) {
        j.row(base + 3 * f + k) = p.transpose();
        parents.push_back(k == 0 ? wrist : base + 3 * f + k - 1);
        p += 0.03f * h;
      }
    }
    Eigen::Vector3f t = w + 0.02f * h + 0.03f * radial;
    const Eigen::Vector3f thumb_dir = (h + radial).normalized();
    for (int k = 0; k < 3; ++k) {
      j.row(base + 12 + k) = t.transpose();
      parents.push_back(k == 0 ? wrist : base + 12 + k - 1);
      t += 0.03f * thumb_dir;
    }
  }
  return make_skeleton(*names, parents, j);
}

// The left palm a 24-joint skeleton is given: the hanging hand's palm (facing -x, the thigh)
// turned by the smallest rotation from hanging onto the hand's axis `h` (Rodrigues' formula).
Eigen::Vector3f turned_palm(const Eigen::Vector3f& h) {
  const Eigen::Vector3f down(0, -1, 0), v(-1, 0, 0);
  const Eigen::Vector3f axis = down.cross(h);
  const float sin = axis.norm(), cos = down.dot(h);
  const Eigen::Vector3f k = axis / sin;
  return v * cos + k.cross(v) * sin + k * k.dot(v) * (1.0f - cos);
}

body::PosedBody posed(const Skeleton& s, const std::string& pose) {
  const body::PoseDefinition* p = body::find_pose(pose);
  REQUIRE(p);
  body::PosedBody b = body::pose_body(s.model, s.rest, *p);
  INFO(pose << ": " << b.reason);
  REQUIRE(b.available);
  return b;
}

Eigen::Vector3f bone(const body::Vertices& joints, const body::Model& m, const std::string& a,
                     const std::string& b) {
  return (joints.row(index_of(m, b)) - joints.row(index_of(m, a))).transpose().normalized();
}

const Eigen::Vector3f kDown(0, -1, 0), kUp(0, 1, 0), kForward(0, 0, 1);

}  // namespace

TEST_CASE("pose library: every pose has a name, a description and a unique entry",
          "[pose-library]") {
  const auto& poses = body::pose_library();
  CHECK(poses.size() == 12u);
  for (const auto& p : poses) {
    CHECK(!p.description.empty());
    CHECK(body::find_pose(p.name) == &p);
  }
  CHECK(body::find_pose("cartwheel") == nullptr);
  CHECK(body::pose_names().find("shoulder-abduct-170-from-t") != std::string::npos);
}

TEST_CASE("pose library: shoulder abduction sets the upper arm's angle from hanging",
          "[pose-library]") {
  const Skeleton s = smpl_skeleton();
  for (const char* name : {"shoulder-abduct-80", "shoulder-abduct-170", "shoulder-abduct-80-from-t",
                           "shoulder-abduct-170-from-t"}) {
    INFO(name);
    const auto b = posed(s, name);
    const double target = std::string(name).find("170") != std::string::npos ? 170.0 : 80.0;
    for (const char* side : {"left", "right"}) {
      const Eigen::Vector3f u = bone(b.posed_joints, s.model, std::string(side) + "_shoulder",
                                     std::string(side) + "_elbow");
      INFO(side << " upper arm " << u.transpose());
      CHECK(degrees_between(u, kDown) == Approx(target).margin(0.1));
      CHECK(std::abs(u.z()) < 1e-3f);                    // in the frontal plane
      CHECK((side[0] == 'l' ? u.x() : -u.x()) > 0.15f);  // out to its own side
    }
    // The T-pose rows start from horizontal arms.
    const bool from_t = std::string(name).find("from-t") != std::string::npos;
    const Eigen::Vector3f rest_upper = bone(b.rest_joints, s.model, "left_shoulder", "left_elbow");
    CHECK(degrees_between(rest_upper, Eigen::Vector3f::UnitX()) ==
          Approx(from_t ? 0.0 : 45.0).margin(from_t ? 0.05 : 5.0));
  }
  // After 170 degrees the left upper arm points nearly up.
  const auto up = posed(s, "shoulder-abduct-170");
  CHECK(degrees_between(bone(up.posed_joints, s.model, "left_shoulder", "left_elbow"), kUp) ==
        Approx(10.0).margin(0.1));
}

TEST_CASE("pose library: flexions of shoulder, elbow, hip and knee bend the expected way",
          "[pose-library]") {
  const Skeleton s = smpl_skeleton();
  const auto flex = posed(s, "shoulder-flex-90");
  CHECK(degrees_between(bone(flex.posed_joints, s.model, "left_shoulder", "left_elbow"),
                        kForward) == Approx(0.0).margin(0.1));
  CHECK(degrees_between(bone(flex.posed_joints, s.model, "right_shoulder", "right_elbow"),
                        kForward) == Approx(0.0).margin(0.1));

  const auto elbow = posed(s, "elbow-130");
  for (const char* side : {"left", "right"}) {
    const std::string sd(side);
    const Eigen::Vector3f upper =
        bone(elbow.posed_joints, s.model, sd + "_shoulder", sd + "_elbow");
    const Eigen::Vector3f fore = bone(elbow.posed_joints, s.model, sd + "_elbow", sd + "_wrist");
    INFO(side);
    CHECK(
        degrees_between(upper, kArm.cwiseProduct(Eigen::Vector3f(side[0] == 'l' ? 1 : -1, 1, 1))) ==
        Approx(0.0).margin(0.05));  // the upper arm stays
    CHECK(degrees_between(upper, fore) == Approx(130.0).margin(0.1));
    // Toward the front: the bend lies in the plane of the upper arm and the forward axis.
    const Eigen::Vector3f normal = upper.cross(kForward).normalized();
    CHECK(std::abs(fore.dot(normal)) < 1e-3f);
    CHECK(fore.z() > 0.5f);
  }

  const auto hip = posed(s, "hip-flex-90");
  CHECK(degrees_between(bone(hip.posed_joints, s.model, "left_hip", "left_knee"), kForward) ==
        Approx(0.0).margin(0.1));
  CHECK(degrees_between(bone(hip.posed_joints, s.model, "right_hip", "right_knee"), kForward) ==
        Approx(0.0).margin(0.1));

  const auto knee = posed(s, "knee-130");
  const Eigen::Vector3f thigh = bone(knee.posed_joints, s.model, "left_hip", "left_knee");
  const Eigen::Vector3f shin = bone(knee.posed_joints, s.model, "left_knee", "left_ankle");
  const Eigen::Vector3f rest_shin = bone(knee.rest_joints, s.model, "left_knee", "left_ankle");
  const Eigen::Vector3f rest_thigh = bone(knee.rest_joints, s.model, "left_hip", "left_knee");
  CHECK(degrees_between(rest_shin, shin) == Approx(130.0).margin(0.1));
  CHECK(degrees_between(thigh, rest_thigh) == Approx(0.0).margin(0.01));
  CHECK(shin.z() < -0.5f);  // backward
}

TEST_CASE("pose library: forearm twist, wrist flexion and head turn", "[pose-library]") {
  const Skeleton s = smpl_skeleton();
  const auto twist = posed(s, "forearm-twist-90");
  for (int side = 0; side < 2; ++side) {
    const std::string sd = side == 0 ? "left" : "right";
    const Eigen::Matrix3f r = twist.local[std::size_t(index_of(s.model, sd + "_elbow"))];
    const Eigen::AngleAxisf aa(r);
    const Eigen::Vector3f fore = bone(twist.rest_joints, s.model, sd + "_elbow", sd + "_wrist");
    INFO(sd);
    CHECK(aa.angle() * 180.0 / kPi == Approx(90.0).margin(0.05));
    CHECK(std::abs(aa.axis().dot(fore)) == Approx(1.0).margin(1e-4));
    // Pronation: the forward-pointing thumb side turns toward the body.
    const Eigen::Vector3f thumb = r * kForward;
    CHECK((side == 0 ? thumb.x() : -thumb.x()) < -0.5f);
    // The forearm's axis itself does not move.
    CHECK(degrees_between(bone(twist.posed_joints, s.model, sd + "_elbow", sd + "_hand"), fore) ==
          Approx(0.0).margin(0.05));
  }

  // Without finger joints the palm is taken to face the thigh as on a hanging arm, turned with
  // the arm (down and in in the A-pose): the hand bends 60 degrees toward it.
  const auto wrist = posed(s, "wrist-flex-60");
  const Eigen::Vector3f hand = bone(wrist.posed_joints, s.model, "left_wrist", "left_hand");
  CHECK(degrees_between(hand, kArm) == Approx(60.0).margin(0.1));
  const Eigen::Vector3f palm = turned_palm(kArm);
  CHECK(palm.x() < -0.5f);  // toward the body
  CHECK(palm.y() < -0.5f);  // and down
  const Eigen::Vector3f expected = std::cos(kPi / 3) * kArm + std::sin(kPi / 3) * palm;
  CHECK(degrees_between(hand, expected) == Approx(0.0).margin(0.1));

  const auto head = posed(s, "head-turn-60");
  const Eigen::Matrix3f r = head.local[std::size_t(index_of(s.model, "head"))];
  const Eigen::Vector3f face = r * kForward;
  CHECK(face.x() == Approx(std::sin(kPi / 3)).margin(1e-5));  // toward the subject's left
  CHECK(face.y() == Approx(0.0).margin(1e-5));
  CHECK(face.z() == Approx(std::cos(kPi / 3)).margin(1e-5));
  // Only the head turns.
  for (std::size_t j = 0; j < head.local.size(); ++j) {
    if (int(j) != index_of(s.model, "head")) CHECK(head.local[j].isIdentity(1e-6f));
  }
}

TEST_CASE("pose library: a fist needs finger joints - with SMPL-X's hands every finger curls",
          "[pose-library]") {
  const Skeleton smpl = smpl_skeleton();
  const auto none = body::pose_body(smpl.model, smpl.rest, *body::find_pose("fist"));
  CHECK_FALSE(none.available);
  CHECK(none.reason.find("left_index1") != std::string::npos);
  CHECK(body::measured_joints(smpl.model, smpl.rest.joints, *body::find_pose("fist")).empty());

  const Skeleton x = smplx_skeleton();
  const auto fist = posed(x, "fist");
  for (int side = 0; side < 2; ++side) {
    const std::string sd = side == 0 ? "left" : "right";
    Eigen::Vector3f palm = left_palm();
    if (side == 1) palm.x() = -palm.x();
    for (const char* finger : {"index", "middle", "ring", "pinky"}) {
      const std::string f = sd + "_" + finger;
      INFO(f);
      const Eigen::Vector3f rest = bone(fist.rest_joints, x.model, f + "1", f + "2");
      const Eigen::Vector3f now = bone(fist.posed_joints, x.model, f + "1", f + "2");
      CHECK(degrees_between(rest, now) == Approx(80.0).margin(0.1));
      CHECK(now.dot(palm) > 0.97f);  // toward the palm
      // The middle segment turns twice over: 160 degrees from its rest direction.
      const Eigen::Vector3f second = bone(fist.posed_joints, x.model, f + "2", f + "3");
      CHECK(degrees_between(rest, second) == Approx(160.0).margin(0.2));
      const Eigen::AngleAxisf tip(fist.local[std::size_t(index_of(x.model, f + "3"))]);
      CHECK(tip.angle() * 180.0 / kPi == Approx(80.0).margin(0.05));
    }
    // The thumb closes toward the palm within its range.
    const Eigen::Vector3f rest = bone(fist.rest_joints, x.model, sd + "_thumb1", sd + "_thumb2");
    const Eigen::Vector3f now = bone(fist.posed_joints, x.model, sd + "_thumb1", sd + "_thumb2");
    CHECK(degrees_between(rest, now) == Approx(40.0).margin(0.1));
    CHECK(now.dot(palm) > rest.dot(palm) + 0.3f);
  }
  // The wrist and the arm are left alone.
  CHECK(fist.local[std::size_t(index_of(x.model, "left_wrist"))].isIdentity(1e-6f));
  // Measured at the 15 left finger joints.
  CHECK(body::measured_joints(x.model, x.rest.joints, *body::find_pose("fist")).size() == 15u);

  // With fingers, the wrist flexes toward the palm the knuckles define.
  const auto wrist = posed(x, "wrist-flex-60");
  const Eigen::Vector3f rest_hand = bone(wrist.rest_joints, x.model, "left_wrist", "left_middle1");
  const Eigen::Vector3f hand = bone(wrist.posed_joints, x.model, "left_wrist", "left_middle1");
  CHECK(degrees_between(rest_hand, hand) == Approx(60.0).margin(0.1));
  CHECK(hand.dot(left_palm()) == Approx(std::sin(kPi / 3)).margin(0.01));
}

TEST_CASE("pose library: the measured region's radius scales with the bones", "[pose-library]") {
  const Skeleton s = smpl_skeleton();
  const auto shoulder =
      body::measured_joints(s.model, s.rest.joints, *body::find_pose("shoulder-flex-90"));
  REQUIRE(shoulder.size() == 1u);
  CHECK(shoulder[0].joint == index_of(s.model, "left_shoulder"));
  CHECK(shoulder[0].radius == Approx(0.5 * 0.27).epsilon(1e-4));
  const auto head = body::measured_joints(s.model, s.rest.joints, *body::find_pose("head-turn-60"));
  REQUIRE(head.size() == 1u);
  CHECK(head[0].joint == index_of(s.model, "head"));
  CHECK(head[0].radius == Approx(std::hypot(0.09, 0.02)).epsilon(1e-4));
}

TEST_CASE("pose library: a skeleton without named joints cannot be posed, and says why",
          "[pose-library]") {
  Skeleton s = smpl_skeleton();
  s.model.joint_names[18] = "elbow_l";  // a foreign name for the left elbow
  const auto b = body::pose_body(s.model, s.rest, *body::find_pose("elbow-130"));
  CHECK_FALSE(b.available);
  CHECK(b.reason.find("left_elbow") != std::string::npos);
  // Coincident joints are reported too, not turned into NaN.
  Skeleton c = smpl_skeleton();
  c.rest.joints.row(18) = c.rest.joints.row(16);
  c.rest.vertices = c.rest.joints;
  const auto d = body::pose_body(c.model, c.rest, *body::find_pose("shoulder-flex-90"));
  CHECK_FALSE(d.available);
  CHECK(d.reason.find("coincide") != std::string::npos);
}

TEST_CASE("pose benchmark: bodies are the mean and +-3 on each component", "[pose-library]") {
  body::Model m = smpl_skeleton().model;
  m.shapedirs = Eigen::MatrixXf::Zero(3 * 24, 4);
  const auto bodies = body::benchmark_bodies(m, 2);
  REQUIRE(bodies.size() == 5u);
  CHECK(bodies[0].label == "mean");
  CHECK(bodies[3].label == "c2-3");
  CHECK(bodies[3].betas[1] == -3.0f);
  CHECK(bodies[4].betas[1] == 3.0f);
  CHECK(bodies[4].betas.sum() == 3.0f);
  CHECK_THROWS_AS(body::benchmark_bodies(m, 5), body::ModelError);
}

TEST_CASE("pose benchmark: the report puts models side by side with pass and fail",
          "[pose-library]") {
  auto model = [](const std::string& label, double volume, double fold, int crossings) {
    body::ModelBenchmark m;
    m.label = label;
    m.model_name = label + " model";
    m.bodies = {{"mean", Eigen::VectorXf::Zero(1)}};
    for (const auto& p : body::pose_library()) {
      body::PoseResult r;
      r.pose = &p;
      r.available = !p.hand_contact;
      if (!r.available) r.reason = "the skeleton has no left_index1";
      r.volume_worst = r.volume_mean = volume;
      r.fold_worst = r.fold_mean = fold;
      r.intersections_worst = crossings;
      r.intersections_mean = crossings;
      r.pass = std::abs(volume) <= 8 && fold <= 60 && crossings == 0;
      if (!r.pass && r.available) r.failed = "volume";
      body::PoseFigures f;
      f.volume_change_percent = volume;
      f.sharpest_fold_degrees = fold;
      f.intersections.pairs = crossings;
      if (r.available) r.per_body = {f};
      m.poses.push_back(r);
    }
    return m;
  };
  const std::string md =
      body::pose_benchmark_markdown({model("old.npz", -12.5, 80, 3), model("new.npz", -2.0, 30, 0)},
                                    {}, "bench-pose ...", "pose-benchmark.png");
  for (const auto& p : body::pose_library())
    CHECK(md.find("| " + p.name + " |") != std::string::npos);
  CHECK(md.find("old.npz: volume %") != std::string::npos);
  CHECK(md.find("new.npz: volume %") != std::string::npos);
  CHECK(md.find("| -12.5 (-12.5) | 80 (80) | 3 (3.0) | **fail** (volume) | -2.0 (-2.0) | 30 (30) "
                "| 0 (0.0) | pass |") != std::string::npos);
  CHECK(md.find("| **passing** | | | | 0 of 11 | | | | 11 of 11 |") != std::string::npos);
  CHECK(md.find("fist: not available (the skeleton has no left_index1)") != std::string::npos);
  CHECK(md.find("](pose-benchmark.png)") != std::string::npos);
}
