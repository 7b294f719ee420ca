#include "pose_correctives.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "npz_writer.hpp"

namespace default_model {

namespace {

Eigen::Matrix3d turn(const Vec3& axis, double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

// The smallest rotation taking direction a onto direction b.
Eigen::Matrix3d between(const Vec3& a, const Vec3& b) {
  return Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix();
}

// A finger joint's flexion: its segment's direction (the last joint continues the segment
// before it, as it has no child) crossed with the palm's normal, or for the thumb with the
// direction across the palm to the little finger's side: the axes the pose library's fist
// turns the fingers about (src/body/pose_library.cpp).
std::vector<Eigen::Matrix3d> finger_rotations(int joint, const SmplxRig& rig) {
  const int side = (joint - kSmplxHandsBegin) / 15;
  const int finger = (joint - kSmplxHandsBegin) % 15 / 3;
  const int k = (joint - kSmplxHandsBegin) % 3;
  const int chain = joint - k;
  const auto at = [&](int f, int i) {
    return rig.joints[kSmplxHandsBegin + 15 * side + 3 * f + i];
  };
  const int wrist = kLeftWrist + side;
  const Vec3 h = (at(1, 0) - rig.joints[wrist]).normalized();  // to the middle knuckle
  const Vec3 radial = at(0, 0) - at(2, 0);                     // pinky -> index knuckle
  Vec3 palm = (side == 0 ? 1.0 : -1.0) * h.cross(radial);
  palm = (palm - palm.dot(h) * h).normalized();
  const Vec3 d = k < 2 ? (rig.joints[chain + k + 1] - rig.joints[chain + k]).normalized()
                       : (rig.joints[chain + 2] - rig.joints[chain + 1]).normalized();
  std::vector<Eigen::Matrix3d> out;
  if (finger == 4) {
    Vec3 ulnar = at(2, 0) - at(0, 0);
    ulnar -= ulnar.dot(h) * h;
    const Vec3 across = (palm + ulnar.normalized()).normalized();
    const double limit = k == 0 ? 40.0 : (k == 1 ? 60.0 : 80.0);  // the fist's thumb ranges
    for (double a : {-15.0, 0.3 * limit, 0.6 * limit, limit})
      out.push_back(turn(d.cross(across), a));
    return out;
  }
  for (double a : {-20.0, 20.0, 45.0, 80.0, 100.0}) out.push_back(turn(d.cross(palm), a));
  if (k == 0) {
    for (double a : {-15.0, 15.0}) out.push_back(turn(palm, a));  // spread and closed
  }
  return out;
}

// Rotations of one joint that people make, the joint's range in the body's frame (y up, +z
// forward, the subject's left +x; sx = +1 left, -1 right): the linear fit in R - I is only as
// good as its samples are like the poses it is used for.
std::vector<Eigen::Matrix3d> joint_rotations(int joint, const SmplxRig& rig) {
  if (joint >= kSmplxHandsBegin && joint < kSmplxJoints) return finger_rotations(joint, rig);
  const int side = (joint == kLeftShoulder || joint == kLeftElbow || joint == kLeftWrist ||
                    joint == kLeftHip || joint == kLeftKnee || joint == kLeftAnkle)
                       ? 0
                       : 1;
  const double sx = side == 0 ? 1.0 : -1.0;
  const Vec3 X(1, 0, 0), Z(0, 0, 1);
  std::vector<Eigen::Matrix3d> out;
  const auto dir = [&](int a, int b) { return (rig.joints[b] - rig.joints[a]).normalized(); };
  if (joint == kLeftShoulder || joint == kRightShoulder) {
    const Vec3 d = dir(joint, joint + 2);  // to the elbow
    // Up the side (abduction) to 170 degrees from hanging, down to the body, forward and up,
    // back, and turned about the arm.
    for (double a : {10.0, 80.0, 120.0, 170.0})
      out.push_back(between(d, Vec3(sx * std::sin(a * M_PI / 180), -std::cos(a * M_PI / 180), 0)));
    for (double a : {45.0, 90.0, 150.0})
      out.push_back(between(
          d, Vec3(0.2 * sx, -std::cos(a * M_PI / 180), std::sin(a * M_PI / 180)).normalized()));
    out.push_back(between(d, Vec3(0.3 * sx, -0.8, -0.5).normalized()));
    for (double a : {-60.0, 60.0}) out.push_back(turn(d, a));
  } else if (joint == kLeftElbow || joint == kRightElbow) {
    const Vec3 d = dir(joint - 2, joint);        // the upper arm
    const Vec3 f = dir(joint, joint + 2);        // the forearm
    const Vec3 hinge = d.cross(Z).normalized();  // turns the forearm forwards
    for (double a : {30.0, 60.0, 90.0, 130.0, 150.0}) out.push_back(turn(hinge, a));
    for (double a : {-90.0, -45.0, 45.0, 90.0}) out.push_back(turn(f, a));
  } else if (joint == kLeftWrist || joint == kRightWrist) {
    const Vec3 f = dir(joint - 2, joint);
    // The palm faces the thigh in the A-pose: flexion turns the hand towards -x (left hand).
    const Vec3 palm = (Vec3(-sx, 0, 0) - f * f.dot(Vec3(-sx, 0, 0))).normalized();
    const Vec3 flex = f.cross(palm).normalized();
    for (double a : {-60.0, -30.0, 30.0, 60.0, 80.0}) out.push_back(turn(flex, a));
    for (double a : {-30.0, 30.0}) out.push_back(turn(palm, a));
  } else if (joint == kLeftKnee || joint == kRightKnee) {
    for (double a : {30.0, 60.0, 90.0, 130.0, 150.0}) out.push_back(turn(X, a));
    out.push_back(turn(X, -5.0));
  } else if (joint == kLeftAnkle || joint == kRightAnkle) {
    for (double a : {-40.0, -20.0, 20.0, 40.0}) out.push_back(turn(X, a));
    for (double a : {-20.0, 20.0}) out.push_back(turn(Z, a));
  } else if (joint == kLeftHip || joint == kRightHip) {
    const Vec3 d = dir(joint, joint + 3);  // to the knee
    // Forward (flexion, the shin's turn(X, +a) is backward), back, out to the side, and turned
    // about the thigh.
    for (double a : {30.0, 60.0, 90.0, 120.0}) out.push_back(turn(X, -a));
    out.push_back(turn(X, 20.0));
    for (double a : {25.0, 50.0}) out.push_back(turn(Z, sx * a));
    for (double a : {-40.0, 40.0}) out.push_back(turn(d, a));
  } else if (joint == kHead) {
    const Vec3 Y(0, 1, 0);
    // Turned left and right, nodded, tilted to each shoulder.
    for (double a : {-75.0, -40.0, 40.0, 75.0}) out.push_back(turn(Y, a));
    for (double a : {-35.0, 35.0}) out.push_back(turn(X, a));
    for (double a : {-30.0, 30.0}) out.push_back(turn(Z, a));
  }
  return out;
}

struct JointFit {
  std::vector<int> zone;                                  // blend zone vertices
  std::vector<Eigen::Matrix<double, 3, 9>> coefficients;  // per zone vertex
  double skinning_error = 0, fitted_error = 0;            // sums over samples and vertices
  long count = 0;
  int poses = 0;
};

// What a joint's blend zone should look like when the joint turns.
enum class PosedTarget {
  // The posed template: the primitives after the joint turned about it (limbs, whose
  // primitives carry the skin on both sides of the joint).
  kTemplate,
  // Each vertex turned about the joint by its share of the rotation (the same axis, the angle
  // times the vertex's weight), so it keeps its distance from the joint: the result that dual
  // quaternion skinning gives for one joint (Kavan et al. 2008) and the one that keeps a
  // twisted or bent blend zone from collapsing onto the chord as linear blending does. For the
  // joints where the union of primitives is no surface the skin can follow: the shoulders and
  // hips (where the limbs meet the trunk) and the head on the neck.
  kRotationShare,
};

// Elbows, knees and ankles follow the posed template. At the shoulders, hips and head the
// posed union of primitives is not a surface the skin can follow (projecting the armpit's
// vertices onto it jumped between the arm and the chest and tore the skin in the pose
// benchmark), so there each vertex keeps its distance from the joint instead. The wrists get
// none: the palm's vertices jumped between the palm and the fingers the same way, and plain
// skinning already keeps the wrist within the pose targets.
const std::vector<int>& template_joints() {
  static const std::vector<int> j = {kLeftElbow, kRightElbow, kLeftKnee,
                                     kRightKnee, kLeftAnkle,  kRightAnkle};
  return j;
}
// The fingers too: linear blending pulls a bent knuckle's skin onto the chord (a fist lost 27 %
// of the volume round its knuckles in the pose benchmark).
const std::vector<int>& rotation_share_joints() {
  static const std::vector<int> j = [] {
    std::vector<int> joints = {kLeftShoulder, kRightShoulder, kLeftHip, kRightHip, kHead};
    for (int f = kSmplxHandsBegin; f < kSmplxJoints; ++f) joints.push_back(f);
    return joints;
  }();
  return j;
}

// How much of the rotation share's offset a joint takes. Where a limb turns against the
// trunk the whole share over-fills the convex side: at 90 degrees of hip flexion the
// buttock's region gained 16 % volume with it and lost 25 % with none (plain skinning); at 170
// degrees of shoulder abduction the female mean body's shoulder gained 11.5 % (the male's 4 %)
// and lost 44 % with none. The volume is steep in the strength there (6 points per 0.1 at the
// shoulder); 0.65 and 0.9 keep the three mean bodies within 6 % (tuned on the pose benchmark).
double rotation_share_strength(int joint) {
  if (joint == kLeftHip || joint == kRightHip) return 0.65;
  if (joint == kLeftShoulder || joint == kRightShoulder) return 0.9;
  if (joint >= kSmplxHandsBegin && joint < kSmplxJoints) {
    // Per finger joint, knuckle to tip, the fingers' then the thumb's: with one strength for
    // all, the knuckles still lost volume (-12 % at 0.45, -8 % at 0.6) where the middle joints
    // already gained (+7 %, +16 %). These keep every finger joint of the three mean bodies
    // within 5 % in the fist (the worst of their +-3 SD bodies within 7.1 %).
    static constexpr double kFinger[3] = {1.0, 0.1, 0.5}, kThumb[3] = {0.6, 0.95, 0.9};
    const int i = joint - kSmplxHandsBegin;
    return (i % 15 / 3 == 4 ? kThumb : kFinger)[i % 3];
  }
  return 1.0;
}

// The fit of one joint's columns on the rest body P (with the rig's joints at that body's
// joints). The template kind needs the mannequin whose primitives it poses.
JointFit fit_joint(const std::vector<Vec3>& P, const SmplxRig& rig, const Eigen::VectorXd& share,
                   int joint, PosedTarget kind, const Mannequin* mannequin) {
  const int V = static_cast<int>(P.size());
  JointFit fit;
  for (int v = 0; v < V; ++v)
    if (share[v] > 0.005 && share[v] < 0.995) fit.zone.push_back(v);
  const std::vector<Eigen::Matrix3d> rotations = joint_rotations(joint, rig);
  const int S = static_cast<int>(rotations.size()), n = static_cast<int>(fit.zone.size());
  if (n == 0 || S == 0) return fit;
  const Vec3 c = rig.joints[joint];
  const double strength = rotation_share_strength(joint);
  Eigen::MatrixXd features(9, S);
  std::vector<Eigen::MatrixXd> targets(n, Eigen::MatrixXd::Zero(3, S));
  for (int s = 0; s < S; ++s) {
    const Eigen::Matrix3d& R = rotations[s];
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> d = R - Eigen::Matrix3d::Identity();
    features.col(s) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(d.data());
    const JointPose pose =
        kind == PosedTarget::kTemplate ? joint_pose(joint, R, mannequin->skeleton()) : JointPose{};
    const Eigen::AngleAxisd turn_of(R);
    for (int i = 0; i < n; ++i) {
      const int v = fit.zone[i];
      const Vec3 skinned = (1.0 - share[v]) * P[v] + share[v] * (c + R * (P[v] - c));
      Vec3 r;
      if (kind == PosedTarget::kTemplate) {
        r = mannequin->project(skinned, 8, &pose) - skinned;
        // Farther than 3 cm the projection found another part of the body (the forearm
        // pressed into the biceps): nothing to learn there.
        if (r.norm() > 0.03) r.setZero();
      } else {
        const Eigen::AngleAxisd part(share[v] * turn_of.angle(), turn_of.axis());
        r = strength * (c + part.toRotationMatrix() * (P[v] - c) - skinned);
      }
      const Eigen::Matrix3d M = (1.0 - share[v]) * Eigen::Matrix3d::Identity() + share[v] * R;
      targets[i].col(s) = M.inverse() * r;
      fit.skinning_error += r.norm();
    }
  }
  // Ridge regression of each vertex's offsets on the nine features (one normal matrix).
  const Eigen::Matrix<double, 9, 9> gram = features * features.transpose();
  const Eigen::Matrix<double, 9, 9> inverse =
      (gram + 1e-3 * gram.trace() / 9.0 * Eigen::Matrix<double, 9, 9>::Identity()).inverse();
  fit.coefficients.resize(n);
  for (int i = 0; i < n; ++i) {
    fit.coefficients[i] = targets[i] * features.transpose() * inverse;
    // A vertex whose offsets stay under half a millimetre in every sample pose keeps none.
    if ((fit.coefficients[i] * features).colwise().norm().maxCoeff() < 5e-4)
      fit.coefficients[i].setZero();
    const Eigen::MatrixXd residual = targets[i] - fit.coefficients[i] * features;
    const int v = fit.zone[i];
    for (int s = 0; s < S; ++s) {
      const Eigen::Matrix3d M =
          (1.0 - share[v]) * Eigen::Matrix3d::Identity() + share[v] * rotations[s];
      fit.fitted_error += (M * residual.col(s)).norm();
    }
  }
  fit.count = static_cast<long>(n) * S;
  fit.poses = S;
  return fit;
}

// A coefficient rounded to a multiple of 2^-17 m (7.6 micrometres): the offsets change by at
// most 0.1 mm, and deflate packs posedirs three times tighter (it took 2 MB of each 6.3 MB
// file unrounded).
double quantised(double c) {
  return rounded_to_binary_step(c, 17);
}

// Fits the given joints' columns of posedirs (3V x 9 (J - 1)) on the rest body P, in parallel.
PoseCorrectiveReport fit_joints(const std::vector<int>& joints, PosedTarget kind,
                                const std::vector<Vec3>& P, const SmplxRig& rig,
                                const Eigen::MatrixXd& weights, int threads,
                                const Mannequin* mannequin, Eigen::MatrixXf& posedirs) {
  const int V = static_cast<int>(P.size());
  const int J = rig.size();
  std::vector<std::vector<char>> in_subtree(J, std::vector<char>(J, 0));
  for (int j = 0; j < J; ++j)
    for (int k = j; k >= 0; k = rig.parents[k]) in_subtree[k][j] = 1;
  std::vector<JointFit> fits(joints.size());
  std::vector<std::thread> pool;
  const int workers = std::max(1, threads);
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      for (std::size_t i = w; i < joints.size(); i += workers) {
        Eigen::VectorXd share = Eigen::VectorXd::Zero(V);
        for (int k = 0; k < J; ++k)
          if (in_subtree[joints[i]][k]) share += weights.col(k);
        fits[i] = fit_joint(P, rig, share, joints[i], kind, mannequin);
      }
    });
  for (auto& th : pool) th.join();

  PoseCorrectiveReport r;
  double skin = 0, fitted = 0;
  long count = 0;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const JointFit& fit = fits[i];
    posedirs.middleCols<9>(9 * (joints[i] - 1)).setZero();
    if (fit.count == 0) continue;
    ++r.joints;
    r.poses += fit.poses;
    for (std::size_t k = 0; k < fit.zone.size(); ++k)
      posedirs.block<3, 9>(3 * fit.zone[k], 9 * (joints[i] - 1)) =
          fit.coefficients[k].unaryExpr(&quantised).cast<float>();
    skin += fit.skinning_error;
    fitted += fit.fitted_error;
    count += fit.count;
  }
  r.skinning_error_mm = count ? 1e3 * skin / count : 0;
  r.fitted_error_mm = count ? 1e3 * fitted / count : 0;
  return r;
}

}  // namespace

Eigen::MatrixXf fit_pose_correctives(const Mannequin& mannequin, const TriMesh& mesh,
                                     const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                     int threads, PoseCorrectiveReport* report) {
  const int V = static_cast<int>(mesh.vertices.size());
  Eigen::MatrixXf posedirs = Eigen::MatrixXf::Zero(3 * V, 9 * (rig.size() - 1));
  const PoseCorrectiveReport limbs =
      fit_joints(template_joints(), PosedTarget::kTemplate, mesh.vertices, rig, weights, threads,
                 &mannequin, posedirs);
  if (report) *report = limbs;
  return posedirs;
}

void fit_rotation_share_correctives(const std::vector<Vec3>& rest, const SmplxRig& rig,
                                    const Eigen::MatrixXd& weights, int threads,
                                    Eigen::MatrixXf& posedirs, PoseCorrectiveReport* report) {
  const PoseCorrectiveReport shared =
      fit_joints(rotation_share_joints(), PosedTarget::kRotationShare, rest, rig, weights, threads,
                 nullptr, posedirs);
  if (report) {
    report->rotation_share_joints = shared.joints;
    report->rotation_share_poses = shared.poses;
  }
}

std::string PoseCorrectiveReport::describe() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "pose correctives for %d joints from %d posed templates: skinning %.1f mm from "
                "the posed template on average in the blend zones, %.1f mm with the "
                "correctives; %d joints from %d poses keep the blend zone's distance from the "
                "joint",
                joints, poses, skinning_error_mm, fitted_error_mm, rotation_share_joints,
                rotation_share_poses);
  return buf;
}

}  // namespace default_model
