// The template mannequin of the default body model as an implicit surface: a smooth union of
// tapered elliptic capsules, ellipsoids and a lofted torso, laid out along SMPL's 24 joints in
// an A-pose. Metres, y up, facing +z, the subject's left on +x, soles at y = 0, 1.70 m tall.
// The field is a signed distance estimate: negative inside, positive outside.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace default_model {

using Vec3 = Eigen::Vector3d;

constexpr int kJointCount = 24;

// SMPL's joint names and parents (root's parent -1), in SMPL's order.
const std::array<const char*, kJointCount>& joint_names();
const std::array<int, kJointCount>& joint_parents();

enum Joint : int {
  kPelvis = 0,
  kLeftHip,
  kRightHip,
  kSpine1,
  kLeftKnee,
  kRightKnee,
  kSpine2,
  kLeftAnkle,
  kRightAnkle,
  kSpine3,
  kLeftFoot,
  kRightFoot,
  kNeck,
  kLeftCollar,
  kRightCollar,
  kHead,
  kLeftShoulder,
  kRightShoulder,
  kLeftElbow,
  kRightElbow,
  kLeftWrist,
  kRightWrist,
  kLeftHand,
  kRightHand
};

// The next joint down a limb (hip -> knee -> ankle -> foot, shoulder -> elbow -> wrist ->
// hand): SMPL's order interleaves the two sides and the spine, so a leg steps by 3 and an arm
// by 2.
constexpr int limb_child(int joint) {
  return joint == kLeftHip || joint == kRightHip || joint == kLeftKnee || joint == kRightKnee ||
                 joint == kLeftAnkle || joint == kRightAnkle
             ? joint + 3
             : joint + 2;
}

// The rest skeleton: each joint's position and the segment ("bone") that the joint drives,
// from bone_start to bone_end (for most joints bone_start is the joint itself), with the
// segment's typical radius (used to normalise distances when computing skin weights).
struct Skeleton {
  std::array<Vec3, kJointCount> joints;
  std::array<Vec3, kJointCount> bone_start;
  std::array<Vec3, kJointCount> bone_end;
  std::array<double, kJointCount> bone_radius;
};

// Where the template's fingers, eyes and jaw are, for the exported SMPL-X rig (rig.hpp).
struct FingerChain {
  std::array<Vec3, 4> points;  // the three joints on the finger's axis, then its tip
};
struct RigLandmarks {
  // [side: 0 = left, 1 = right][SMPL-X's order: index, middle, pinky, ring, thumb]
  std::array<std::array<FingerChain, 5>, 2> fingers;
  std::array<Vec3, 2> eye_centres;  // left (+x), right
  double eye_radius = 0;            // the eyeballs are spheres
  Vec3 jaw, chin;                   // the jaw's joint and the front of its bone
  Vec3 face;                        // the head's second bone runs from the head joint to here
  double mouth_y = 0;               // the mouth line: the jaw moves what lies below it
};

// Tapered capsule with elliptic cross sections; also an ellipsoid when a == b.
struct Capsule {
  Vec3 a, b;            // axis end points
  Vec3 u_hint;          // direction of the first cross-section axis (made orthogonal)
  double ru_a, rv_a;    // cross-section radii at a
  double ru_b, rv_b;    // cross-section radii at b
  double cap_a, cap_b;  // length of the rounded caps beyond a and b
  // Derived frame.
  Vec3 axis, u, v;
  double length = 0;
  void finish();
  double distance(const Vec3& p) const;
  // The same, with the outward direction of the ellipsoidal bound at p (unit; the taper is
  // ignored, which is close enough for deciding how two surfaces meet).
  double distance(const Vec3& p, Vec3* normal) const;
};

// A distance estimate with the (approximate, unit) outward normal direction there.
struct Dist {
  double d = 1e9;
  Vec3 n = Vec3(0, 1, 0);
};

// Torso cross sections: superellipses at key heights, interpolated smoothly in y.
struct TorsoLevel {
  double y, half_width, half_depth, z_center;
};

// One joint of the shape skeleton turned by `rotation` about its rest position, with everything
// after it in the chain (`moved`, per joint of the 24): the template's own primitives follow
// their bones, which makes a posed template that keeps its shape (pose_correctives.hpp).
struct JointPose {
  std::array<char, kJointCount> moved{};
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 to_rest(const Vec3& p) const { return centre + rotation.transpose() * (p - centre); }
};
JointPose joint_pose(int joint, const Eigen::Matrix3d& rotation, const Skeleton& skeleton);

class Mannequin {
 public:
  Mannequin();

  double field(const Vec3& p) const { return field(p, nullptr); }
  // The field of the template in a pose: only the limbs' primitives move (arms from the
  // shoulder down, legs from the knee down), so poses of other joints are not supported.
  double field(const Vec3& p, const JointPose* pose) const;
  Vec3 gradient(const Vec3& p, const JointPose* pose = nullptr) const;
  // Newton steps along the gradient onto the zero level set.
  Vec3 project(const Vec3& p, int iterations = 5, const JointPose* pose = nullptr) const;
  // Desired edge length of the output mesh near p (finer at hands, face and feet).
  double target_edge(const Vec3& p) const;

  const Skeleton& skeleton() const { return skeleton_; }
  const RigLandmarks& landmarks() const { return landmarks_; }
  Eigen::AlignedBox3d bounds() const;

 private:
  struct Side {
    std::vector<std::pair<Capsule, double>> arm;  // primitive, blend radius into the chain
    std::vector<int> arm_bone;                    // the joint each arm primitive follows
    std::size_t hand_begin = 0;                   // arm[hand_begin..] make the fingers
    Vec3 hand_centre = Vec3::Zero();              // and lie within this sphere
    double hand_radius = 0;
    std::vector<std::pair<Capsule, double>> leg;
    std::vector<int> leg_bone;  // the joint each leg primitive follows (the toes: the foot's)
    std::vector<Capsule> toes;  // joined to the foot, grooved between
    std::vector<std::pair<Capsule, double>> leg_cuts;  // carved out of the foot (the arch)
    Vec3 shoulder;
  };
  double torso_loft(const Vec3& p) const;
  double arm_field(const Side& s, const Vec3& p, const JointPose* pose) const;
  Dist leg_field(const Side& s, const Vec3& p, const JointPose* pose) const;
  double trunk_field(const Vec3& p) const;  // loft and torso parts
  double trunk_and_legs(const Vec3& p, const JointPose* pose) const;
  // The trunk morphs into the legs between these heights (crotch to hip).
  static constexpr double kMorphBottom = 0.775, kMorphTop = 0.97;

  Skeleton skeleton_;
  RigLandmarks landmarks_;
  std::vector<TorsoLevel> levels_;
  std::vector<std::pair<Capsule, double>> torso_parts_;  // blended into the loft
  std::vector<std::pair<Capsule, double>> head_parts_;
  std::vector<std::pair<Capsule, double>> head_cuts_;     // carved out of the head (eye sockets)
  std::vector<std::pair<Capsule, double>> head_details_;  // added after the cuts (eyes)
  Vec3 head_centre_ = Vec3::Zero();  // every head primitive lies within this sphere
  double head_radius_ = 0;
  std::vector<std::pair<Vec3, double>> fine_spots_;  // finest mesh within these radii (nails)
  std::array<Side, 2> sides_;                        // 0 = left (+x), 1 = right
};

double smooth_min(double a, double b, double k);
// Smooth union that blends only where the two surfaces cross at an angle: where they run
// side by side (nearly parallel normals, e.g. a thigh inside the hip, a calf overlapping the
// thigh at the knee) the plain polynomial smooth-min would inflate them by up to k / 4 over
// the whole overlap and leave a band with a step where the overlap ends; there this one
// takes the plain union instead, and it blends fully (radius k) where they cross at 50
// degrees or more.
Dist smooth_union(const Dist& a, const Dist& b, double k);
double smoothstep(double e0, double e1, double x);

}  // namespace default_model
