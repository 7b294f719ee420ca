#include "body/pose_library.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

namespace body {

namespace {

constexpr double kPi = 3.14159265358979323846;

const Eigen::Vector3f kDown(0.0f, -1.0f, 0.0f);
const Eigen::Vector3f kForward(0.0f, 0.0f, 1.0f);
const Eigen::Vector3f kUp(0.0f, 1.0f, 0.0f);

float radians(double degrees) {
  return static_cast<float>(degrees * kPi / 180.0);
}

int find_joint(const Model& model, const std::string& name) {
  const auto it = std::find(model.joint_names.begin(), model.joint_names.end(), name);
  return it == model.joint_names.end() ? -1 : static_cast<int>(it - model.joint_names.begin());
}

const char* const kFingers[] = {"index", "middle", "ring", "pinky"};

// Looks up joints by name and collects the names that are missing, so that a pose the
// skeleton cannot make says exactly what it lacks.
class JointLookup {
 public:
  JointLookup(const Model& model, const Vertices& rest) : model_(model), rest_(rest) {}

  int require(const std::string& name) {
    const int j = find_joint(model_, name);
    if (j < 0 && std::find(missing_.begin(), missing_.end(), name) == missing_.end()) {
      missing_.push_back(name);
    }
    return j;
  }
  int optional(const std::string& name) const { return find_joint(model_, name); }
  Eigen::Vector3f at(int j) const { return rest_.row(j).transpose(); }
  // Unit vector from joint a to joint b; zero (and a problem noted) when they coincide.
  Eigen::Vector3f direction(int a, int b) {
    const Eigen::Vector3f d = at(b) - at(a);
    const float n = d.norm();
    if (!(n > 1e-6f)) {
      problem("joints " + model_.joint_names[static_cast<std::size_t>(a)] + " and " +
              model_.joint_names[static_cast<std::size_t>(b)] + " coincide");
      return Eigen::Vector3f::Zero();
    }
    return d / n;
  }
  // Rotation by `angle` (radians) about `axis`; identity (and a problem noted) when the axis
  // is degenerate, e.g. a limb lying along the forward direction it should bend toward.
  Eigen::Matrix3f about(const Eigen::Vector3f& axis, float angle, const std::string& what) {
    const float n = axis.norm();
    if (!(n > 1e-4f)) {
      problem(what);
      return Eigen::Matrix3f::Identity();
    }
    return Eigen::AngleAxisf(angle, axis / n).toRotationMatrix();
  }
  void problem(const std::string& text) {
    if (std::find(problems_.begin(), problems_.end(), text) == problems_.end()) {
      problems_.push_back(text);
    }
  }
  bool ok() const { return missing_.empty() && problems_.empty(); }
  std::string reason() const {
    std::string out;
    // A fist on a skeleton without fingers lacks 30 joints: name a few and count them.
    for (std::size_t i = 0; i < missing_.size() && i < 3; ++i) {
      out += (out.empty() ? "the skeleton has no " : ", ") + missing_[i];
    }
    if (missing_.size() > 3) out += ", ... (" + std::to_string(missing_.size()) + " joints)";
    for (const auto& p : problems_) out += (out.empty() ? "" : "; ") + p;
    return out;
  }

 private:
  const Model& model_;
  const Vertices& rest_;
  std::vector<std::string> missing_;
  std::vector<std::string> problems_;
};

// The limb first brought to hanging straight down by the smallest rotation, then swung from
// there onto `target` (itself the smallest rotation from hanging): the anatomical path, so a
// flexion turns about the lateral axis and an abduction about the forward one whatever the
// rest pose is (A, T), and the limb does not twist about itself on the way.
Eigen::Matrix3f from_hanging(const Eigen::Vector3f& rest_direction, const Eigen::Vector3f& target) {
  return rotation_between(kDown, target) * rotation_between(rest_direction, kDown);
}

// The joint a hand's axis runs to from the wrist: the middle finger's knuckle when the
// skeleton has fingers, SMPL's hand end joint otherwise; -1 if neither.
int hand_tip(const JointLookup& joints, const std::string& side) {
  const int middle1 = joints.optional(side + "_middle1");
  return middle1 >= 0 ? middle1 : joints.optional(side + "_hand");
}

// Unit normal of the palm of one hand (s = +1 left, -1 right), pointing out of the palm,
// orthogonal to the hand's axis. With finger joints: across the knuckles (pinky -> index points
// to the thumb's side) crossed with the hand's axis. Without them (SMPL's 24 joints) the hand
// is taken as a relaxed hand hangs, palm toward the thigh, turned with the arm: the medial
// direction of a hanging hand rotated by the smallest rotation from hanging onto the hand's
// axis. That is how the built-in models hold their hands (palm toward the body in the A-pose,
// checked on a render) and SMPL's template (palm down in its T-like pose).
Eigen::Vector3f palm_normal(JointLookup& joints, const std::string& side, float s,
                            const Eigen::Vector3f& hand_axis) {
  const int index1 = joints.optional(side + "_index1");
  const int pinky1 = joints.optional(side + "_pinky1");
  Eigen::Vector3f palm;
  if (index1 >= 0 && pinky1 >= 0) {
    const Eigen::Vector3f radial = joints.at(index1) - joints.at(pinky1);
    palm = s * hand_axis.cross(radial);
  } else {
    palm = rotation_between(kDown, hand_axis) * Eigen::Vector3f(-s, 0.0f, 0.0f);
  }
  palm -= palm.dot(hand_axis) * hand_axis;
  const float n = palm.norm();
  if (!(n > 1e-4f)) {
    joints.problem("the " + side + " palm's direction is undefined (knuckles along the hand)");
    return Eigen::Vector3f::Zero();
  }
  return palm / n;
}

// Direction of a finger segment starting at joint k of a chain (k1 -> k2 -> k3); the last
// joint has no child in the SMPL family, so it continues the segment before it.
Eigen::Vector3f segment_direction(JointLookup& joints, const int chain[3], int k) {
  return k < 2 ? joints.direction(chain[k], chain[k + 1]) : joints.direction(chain[1], chain[2]);
}

// Sets the rotations of one side (s = +1 left, -1 right). Every rotation is built in the rest
// frame, where every global rotation is identity, so a joint's local rotation is written
// directly in world axes. Axes taken as cross products of two directions mirror with the side
// by themselves (the cross product of mirrored vectors is the mirrored axis reversed), so the
// same positive angle bends both sides alike; a rotation about a limb's own axis (the twist)
// takes the angle with the side's sign.
void pose_side(const PoseDefinition& pose, JointLookup& joints, const std::string& side, float s,
               Rotations& local) {
  const float angle = radians(pose.degrees);
  auto set = [&](int j, const Eigen::Matrix3f& r) {
    if (j >= 0) local[static_cast<std::size_t>(j)] = r;
  };
  switch (pose.kind) {
    case PoseKind::kShoulderAbduct:
    case PoseKind::kShoulderFlex: {
      const int sh = joints.require(side + "_shoulder");
      const int el = joints.require(side + "_elbow");
      if (sh < 0 || el < 0) return;
      const Eigen::Vector3f target =
          pose.kind == PoseKind::kShoulderAbduct
              ? Eigen::Vector3f(s * std::sin(angle), -std::cos(angle), 0.0f)
              : Eigen::Vector3f(0.0f, -std::cos(angle), std::sin(angle));
      set(sh, from_hanging(joints.direction(sh, el), target));
      return;
    }
    case PoseKind::kElbowFlex:
    case PoseKind::kForearmTwist: {
      const int sh = joints.require(side + "_shoulder");
      const int el = joints.require(side + "_elbow");
      const int wr = joints.require(side + "_wrist");
      if (sh < 0 || el < 0 || wr < 0) return;
      if (pose.kind == PoseKind::kElbowFlex) {
        // Rotating about upper x forward turns the forearm from along the upper arm toward
        // the front.
        set(el, joints.about(joints.direction(sh, el).cross(kForward), angle,
                             "the " + side + " upper arm points forward; no elbow flexion axis"));
      } else {
        // Left: +angle about elbow -> wrist turns a hanging arm's thumb from the front to the
        // body (pronation); the right side mirrors it.
        set(el, joints.about(joints.direction(el, wr), s * angle, "no forearm axis"));
      }
      return;
    }
    case PoseKind::kWristFlex: {
      const int wr = joints.require(side + "_wrist");
      const int tip = hand_tip(joints, side);
      if (tip < 0) joints.require(side + "_hand");  // reported as missing
      if (wr < 0 || tip < 0) return;
      const Eigen::Vector3f h = joints.direction(wr, tip);
      set(wr, joints.about(h.cross(palm_normal(joints, side, s, h)), angle, "no wrist axis"));
      return;
    }
    case PoseKind::kHipFlex: {
      const int hip = joints.require(side + "_hip");
      const int knee = joints.require(side + "_knee");
      if (hip < 0 || knee < 0) return;
      const Eigen::Vector3f target(0.0f, -std::cos(angle), std::sin(angle));
      set(hip, from_hanging(joints.direction(hip, knee), target));
      return;
    }
    case PoseKind::kKneeFlex: {
      const int hip = joints.require(side + "_hip");
      const int knee = joints.require(side + "_knee");
      if (hip < 0 || knee < 0) return;
      // About forward x thigh: turns the shin from along the thigh toward the back.
      set(knee, joints.about(kForward.cross(joints.direction(hip, knee)), angle,
                             "the " + side + " thigh points forward; no knee flexion axis"));
      return;
    }
    case PoseKind::kHeadTurn:
      return;  // one joint on the midline; set by pose_rotations
    case PoseKind::kFist: {
      const int wr = joints.require(side + "_wrist");
      int chains[5][3];
      for (int f = 0; f < 4; ++f) {
        for (int k = 0; k < 3; ++k) {
          chains[f][k] = joints.require(side + "_" + kFingers[f] + std::to_string(k + 1));
        }
      }
      for (int k = 0; k < 3; ++k) {
        chains[4][k] = joints.require(side + "_thumb" + std::to_string(k + 1));
      }
      if (!joints.ok() || wr < 0) return;
      const Eigen::Vector3f h = joints.direction(wr, chains[1][0]);
      const Eigen::Vector3f palm = palm_normal(joints, side, s, h);
      for (int f = 0; f < 4; ++f) {
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3f d = segment_direction(joints, chains[f], k);
          set(chains[f][k], joints.about(d.cross(palm), angle, "no finger flexion axis"));
        }
      }
      // The thumb closes over the fingers: toward the palm and across it to the little
      // finger's side, each joint within its anatomical range (base 40, middle 60, tip 80
      // degrees at most), so the thumb ends on the index and middle fingers, not inside them.
      Eigen::Vector3f ulnar = joints.at(chains[3][0]) - joints.at(chains[0][0]);
      ulnar -= ulnar.dot(h) * h;
      const Eigen::Vector3f across = (palm + ulnar.normalized()).normalized();
      const float thumb_limit[3] = {radians(40.0), radians(60.0), radians(80.0)};
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3f d = segment_direction(joints, chains[4], k);
        set(chains[4][k],
            joints.about(d.cross(across), std::min(angle, thumb_limit[k]), "no thumb axis"));
      }
      return;
    }
  }
}

}  // namespace

const std::vector<PoseDefinition>& pose_library() {
  static const std::vector<PoseDefinition> poses = {
      {"shoulder-abduct-80", "upper arms 80 deg from hanging, out to the sides (from A)",
       PoseKind::kShoulderAbduct, 80.0},
      {"shoulder-abduct-170", "upper arms 170 deg from hanging, nearly straight up (from A)",
       PoseKind::kShoulderAbduct, 170.0},
      {"shoulder-abduct-80-from-t", "upper arms 80 deg from hanging, skinned from the T-pose",
       PoseKind::kShoulderAbduct, 80.0, true},
      {"shoulder-abduct-170-from-t", "upper arms 170 deg from hanging, skinned from the T-pose",
       PoseKind::kShoulderAbduct, 170.0, true},
      {"shoulder-flex-90", "upper arms straight forward", PoseKind::kShoulderFlex, 90.0},
      {"elbow-130", "forearms flexed 130 deg toward the front", PoseKind::kElbowFlex, 130.0},
      {"forearm-twist-90", "forearms turned 90 deg about their axis at the elbow (pronation)",
       PoseKind::kForearmTwist, 90.0},
      {"wrist-flex-60", "hands flexed 60 deg toward the palm", PoseKind::kWristFlex, 60.0},
      {"hip-flex-90", "thighs straight forward", PoseKind::kHipFlex, 90.0},
      {"knee-130", "shins flexed 130 deg backward", PoseKind::kKneeFlex, 130.0},
      {"head-turn-60", "head turned 60 deg to its left about the vertical at the head joint",
       PoseKind::kHeadTurn, 60.0},
      {"fist", "every finger joint 80 deg toward the palm, the thumb across it", PoseKind::kFist,
       80.0, false, true},
  };
  return poses;
}

const PoseDefinition* find_pose(const std::string& name) {
  for (const auto& p : pose_library()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::string pose_names() {
  std::string out;
  for (const auto& p : pose_library()) out += (out.empty() ? "" : ", ") + p.name;
  return out;
}

PoseRotations pose_rotations(const Model& model, const Vertices& rest_joints,
                             const PoseDefinition& pose) {
  PoseRotations out;
  const int J = model.joint_count();
  if (rest_joints.rows() != J || static_cast<int>(model.joint_names.size()) != J) {
    throw ModelError(model.name + ": posing needs " + std::to_string(J) +
                     " named rest joints, got " + std::to_string(rest_joints.rows()) +
                     " joints and " + std::to_string(model.joint_names.size()) + " names");
  }
  out.local.assign(static_cast<std::size_t>(J), Eigen::Matrix3f::Identity());
  JointLookup joints(model, rest_joints);
  if (pose.kind == PoseKind::kHeadTurn) {
    // All of the turn at the head joint: it sits at the top of the neck, where the first two
    // vertebrae make about half of the neck's axial rotation, and a turn concentrated there is
    // the harder test of the neck-head blend (a split with the neck joint would halve it).
    const int head = joints.require("head");
    if (head >= 0) {
      out.local[static_cast<std::size_t>(head)] =
          joints.about(kUp, radians(pose.degrees), "no vertical");
    }
  } else {
    pose_side(pose, joints, "left", 1.0f, out.local);
    pose_side(pose, joints, "right", -1.0f, out.local);
  }
  out.available = joints.ok();
  if (!out.available) {
    out.reason = joints.reason();
    out.local.assign(static_cast<std::size_t>(J), Eigen::Matrix3f::Identity());
  }
  return out;
}

std::vector<JointRegion> measured_joints(const Model& model, const Vertices& rest_joints,
                                         const PoseDefinition& pose) {
  JointLookup joints(model, rest_joints);
  // The region around a joint reaches a fixed share of a neighbouring bone: half of the limb
  // bone for shoulders (upper arm), elbows and wrists (forearm), hips (thigh) and knees (shin),
  // so it holds the joint's fold and bulge but not the next joint; the whole neck for the head;
  // one finger segment for each finger joint.
  auto length = [&](int a, int b) { return double((joints.at(b) - joints.at(a)).norm()); };
  std::vector<JointRegion> out;
  auto add = [&](const std::string& name, const std::string& a, const std::string& b,
                 double share) {
    const int j = joints.require(name), ja = joints.require(a), jb = joints.require(b);
    if (j >= 0 && ja >= 0 && jb >= 0) out.push_back({j, share * length(ja, jb)});
  };
  switch (pose.kind) {
    case PoseKind::kShoulderAbduct:
    case PoseKind::kShoulderFlex:
      add("left_shoulder", "left_shoulder", "left_elbow", 0.5);
      break;
    case PoseKind::kElbowFlex:
    case PoseKind::kForearmTwist:
      add("left_elbow", "left_elbow", "left_wrist", 0.5);
      break;
    case PoseKind::kWristFlex:
      add("left_wrist", "left_elbow", "left_wrist", 0.5);
      break;
    case PoseKind::kHipFlex:
      add("left_hip", "left_hip", "left_knee", 0.5);
      break;
    case PoseKind::kKneeFlex:
      add("left_knee", "left_knee", "left_ankle", 0.5);
      break;
    case PoseKind::kHeadTurn:
      add("head", "neck", "head", 1.0);
      break;
    case PoseKind::kFist:
      for (const char* finger : {"index", "middle", "ring", "pinky", "thumb"}) {
        const std::string base = std::string("left_") + finger;
        add(base + "1", base + "1", base + "2", 1.0);
        add(base + "2", base + "2", base + "3", 1.0);
        add(base + "3", base + "2", base + "3", 1.0);
      }
      break;
  }
  if (!joints.ok()) out.clear();
  return out;
}

std::vector<int> hand_joints(const Model& model) {
  std::vector<int> out;
  for (int j = 0; j < model.joint_count() && j < static_cast<int>(model.joint_names.size()); ++j) {
    const std::string& n = model.joint_names[static_cast<std::size_t>(j)];
    for (const char* side : {"left_", "right_"}) {
      if (n.rfind(side, 0) != 0) continue;
      const std::string rest = n.substr(std::string(side).size());
      bool hand = rest == "wrist" || rest == "hand" || rest.rfind("thumb", 0) == 0;
      for (const char* finger : kFingers) hand = hand || rest.rfind(finger, 0) == 0;
      if (hand) out.push_back(j);
    }
  }
  return out;
}

PosedBody pose_body(const Model& model, const BodyMesh& shaped, const PoseDefinition& pose) {
  PosedBody out;
  if (pose.from_t) {
    BodyMesh t;
    try {
      t = t_posed(model, shaped, &out.correctives_applied);
    } catch (const ModelError& e) {
      // A skeleton without SMPL's arm joints has no T-pose; the pose is not available.
      out.reason = std::string("no T-pose: ") + e.what();
      return out;
    }
    out.rest_vertices = t.vertices;
    out.rest_joints = t.joints;
  } else {
    out.rest_vertices = shaped.vertices;
    out.rest_joints = shaped.joints;
  }
  PoseRotations r = pose_rotations(model, out.rest_joints, pose);
  out.available = r.available;
  out.reason = r.reason;
  out.local = std::move(r.local);
  if (!out.available) return out;
  const Skinning skin(model, out.local);
  Vertices v = out.rest_vertices;
  if (!pose.from_t) {
    const Eigen::VectorXf offsets = pose_correctives(model, out.local);
    if (offsets.size() == 3 * v.rows()) {
      Eigen::Map<Eigen::VectorXf>(v.data(), offsets.size()) += offsets;
      out.correctives_applied = true;
    }
  }
  out.posed_vertices = skin.vertices(v, out.rest_joints);
  out.posed_joints = skin.joints(out.rest_joints);
  return out;
}

}  // namespace body
