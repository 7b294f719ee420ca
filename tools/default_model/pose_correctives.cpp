#include "pose_correctives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "body/pose_quality.hpp"
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
    const Vec3 d = dir(joint, limb_child(joint));  // to the elbow
    // Up the side (abduction) to 170 degrees from hanging, down to the body, forward and up,
    // back, and turned about the arm.
    for (double a : {10.0, 80.0, 120.0, 170.0})
      out.push_back(between(d, Vec3(sx * std::sin(a * M_PI / 180), -std::cos(a * M_PI / 180), 0)));
    for (double a : {45.0, 90.0, 150.0})
      out.push_back(between(
          d, Vec3(0.2 * sx, -std::cos(a * M_PI / 180), std::sin(a * M_PI / 180)).normalized()));
    out.push_back(between(d, Vec3(0.3 * sx, -0.8, -0.5).normalized()));
    // Straight forward as the pose library raises an arm (down to hanging, then forward): the
    // arm's front turns up, where the smallest turn from the A-pose turns it in, and its inner
    // skin meets the pectoral.
    out.push_back(between(Vec3(0, -1, 0), Vec3(0, 0, 1)) * between(d, Vec3(0, -1, 0)));
    for (double a : {-60.0, 60.0}) out.push_back(turn(d, a));
  } else if (joint == kLeftElbow || joint == kRightElbow) {
    const Vec3 d = dir(rig.parents[joint], joint);  // the upper arm
    const Vec3 f = dir(joint, limb_child(joint));   // the forearm
    const Vec3 hinge = d.cross(Z).normalized();     // turns the forearm forwards
    for (double a : {30.0, 60.0, 90.0, 130.0, 150.0}) out.push_back(turn(hinge, a));
    for (double a : {-90.0, -45.0, 45.0, 90.0}) out.push_back(turn(f, a));
  } else if (joint == kLeftWrist || joint == kRightWrist) {
    const Vec3 f = dir(rig.parents[joint], joint);
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
    const Vec3 d = dir(joint, limb_child(joint));  // to the knee
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
  // The head turns on a neck whose thickness the first component (size) scales: with the whole
  // share, the neutral model's c1-3 body gained 8.1 % at 60 degrees of head turn (its mean body
  // 1.7 %, c1+3 -2.8 %), as posedirs are one set for all bodies. 0.9 brings the three mean
  // bodies to -0.4 to -0.5 % and keeps every +-3 SD body of components 1-3 within 5.5 %.
  if (joint == kHead) return 0.9;
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

// Flesh in contact at a deeply bent hinge (elbow, knee). The posed template is a blended union
// of primitives, so where the calf presses into the back of the thigh, or the forearm into the
// biceps, both limbs' skins lie inside the other limb and the union has no surface there for
// them: they crossed each other (hundreds of intersecting triangle pairs at 130 degrees in the
// pose benchmark), and projecting onto the union jumped between the limbs and crumpled the
// skin. Flesh pressed together meets on a common surface; here that is the plane bisecting the
// two segments (it holds the hinge's axis), each limb kept on its own side of it.
struct HingeContact {
  Vec3 centre = Vec3::Zero();
  Vec3 up = Vec3::Zero(), down = Vec3::Zero();  // rest directions to the parent and child joints
  Vec3 normal = Vec3::Zero();  // across the joint's plane at rest, to the child's side
  double reach = 0;            // rest distance from the joint within which flesh can meet
  // Pressed flesh ends within 2 gaps of the plane (a vertex on it 1 gap from it).
  static constexpr double kGap = 0.006;

  HingeContact(const SmplxRig& rig, int joint, int parent, int child)
      : centre(rig.joints[joint]),
        up((rig.joints[parent] - centre).normalized()),
        down((rig.joints[child] - centre).normalized()),
        normal((down - up).normalized()),
        reach(0.8 * std::min((rig.joints[parent] - centre).norm(),
                             (rig.joints[child] - centre).norm())) {}

  // `rest`: the vertex at rest; `skinned`: where linear blending puts it; `posed`: where the
  // posed template puts it; R the hinge's turn. Where flesh meets, the skinned vertex is
  // pressed instead of the template's, fading in as it nears the plane and from the side of
  // the bend onto its inside.
  // `pressed_by` (if given) receives how far the vertex was pressed (0 where it was not).
  Vec3 apply(const Vec3& rest, const Vec3& skinned, const Vec3& posed, const Eigen::Matrix3d& R,
             double* pressed_by = nullptr) const {
    if (pressed_by) *pressed_by = 0.0;
    const Vec3 w = R * down;
    const Vec3 inner = up + w;  // into the bend, between the two segments
    if (inner.norm() < 0.1 || (rest - centre).norm() > reach) return posed;
    const Vec3 n = (w - up).normalized();  // the bisecting plane's normal, to the child
    // Which limb the vertex belongs to is the side of the joint's plane it lies on at rest (the
    // crease's vertices on the plane fade out within 3 mm of it).
    const double along = (rest - centre).dot(normal);
    const double limb = std::clamp(std::abs(along) / 0.003, 0.0, 1.0);
    // Only on the bend's inside: the kneecap's and the elbow's outer skin are never pressed.
    const double inside = std::clamp((skinned - centre).dot(inner.normalized()) / 0.02, 0.0, 1.0);
    const double side = along < 0.0 ? -1.0 : 1.0;
    // The distance from the plane on the limb's own side, compressed smoothly below 2 gaps
    // into (0, 2 gaps]: a one-to-one map (hyperbolic below, identity above, C1 where they
    // meet), so flesh that went through the other limb is laid in layers on its own side, in
    // its order. Clamping it onto the plane laid its triangles on top of each other; an
    // exponential laid 3 cm of depth within microns, where flat triangles crossed.
    const double h = side * (skinned - centre).dot(n);
    const double top = 2.0 * kGap;
    // Flesh well clear of the other limb keeps the template's shape.
    const double near = std::clamp((3.0 * top - h) / top, 0.0, 1.0);
    // Faded out over the last quarter of the reach, where the correctives end: a cut there left
    // a step across the back of the thigh.
    const double within = std::clamp((reach - (rest - centre).norm()) / (reach / 4.0), 0.0, 1.0);
    const double t = limb * inside * near * within;
    if (t <= 0.0) return posed;
    const double depth = h >= top ? 0.0 : top * top / (2.0 * top - h) - h;
    if (pressed_by) *pressed_by = t * depth;
    return (1.0 - t) * posed + t * (skinned + depth * side * n);
  }

  // Pressed flesh is not lost: muscle and fat keep their volume and bulge round the contact.
  // Each limb is cut into rings across its axis (2 cm, blended linearly between neighbours);
  // what a ring's pressed vertices gave up (the sum of their depths) its unpressed vertices
  // take back, pushed out from the axis by the same amount shared among them (at most 2 cm).
  // `offsets` are the posed offsets of the vertices `rest`, `pressed` their pressed depths.
  void bulge(const std::vector<Vec3>& rest, const std::vector<double>& pressed,
             const Eigen::Matrix3d& R, std::vector<Vec3>& offsets) const {
    constexpr double kRing = 0.02, kMost = 0.02;
    const int rings = static_cast<int>(reach / kRing) + 2;
    std::vector<double> given(2 * rings, 0.0), takers(2 * rings, 0.0);
    const auto place = [&](const Vec3& p, int* side, int* ring, double* frac) {
      const double along = (p - centre).dot(normal);
      const Vec3& axis = along < 0.0 ? up : down;
      const double a = std::max(0.0, (p - centre).dot(axis)) / kRing;
      *side = along < 0.0 ? 0 : 1;
      *ring = std::min(static_cast<int>(a), rings - 2);
      *frac = std::clamp(a - *ring, 0.0, 1.0);
    };
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if ((rest[i] - centre).norm() > reach) continue;
      int side = 0, ring = 0;
      double frac = 0.0;
      place(rest[i], &side, &ring, &frac);
      std::vector<double>& to = pressed[i] > 0.0 ? given : takers;
      const double amount = pressed[i] > 0.0 ? pressed[i] : 1.0;
      to[side * rings + ring] += (1.0 - frac) * amount;
      to[side * rings + ring + 1] += frac * amount;
    }
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (pressed[i] > 0.0 || (rest[i] - centre).norm() > reach) continue;
      int side = 0, ring = 0;
      double frac = 0.0;
      place(rest[i], &side, &ring, &frac);
      const auto share_of = [&](int k) {
        return takers[k] > 0.0 ? std::min(kMost, given[k] / takers[k]) : 0.0;
      };
      // Faded out over the last third of the reach, where the correctives end.
      const double fade = std::clamp((reach - (rest[i] - centre).norm()) / (reach / 3.0), 0.0, 1.0);
      const double out = fade * ((1.0 - frac) * share_of(side * rings + ring) +
                                 frac * share_of(side * rings + ring + 1));
      if (out <= 0.0) continue;
      const Vec3& axis = side == 0 ? up : down;
      Vec3 radial = (rest[i] - centre) - (rest[i] - centre).dot(axis) * axis;
      if (radial.norm() < 1e-6) continue;
      radial.normalize();
      offsets[i] += out * (side == 0 ? radial : Vec3(R * radial));
    }
  }
};

// Flesh in contact where the arm meets the trunk. Raised straight forward from the A-pose,
// the upper arm's inner skin swings onto the pectoral, which the shoulder's blend zone turns
// with the arm by only a third: each vertex turned by its share of the rotation, the two went
// through each other (about 35 intersecting triangle pairs a side at 90 degrees of flexion).
// There is no plane between a ball joint's limb and a broad trunk as there is between a
// hinge's two segments, so the crossings themselves are resolved: the arm's faces that cross
// a face of the trunk's side (one that turns with the arm by at least 0.3 less) are pushed out
// along that face's normal until they clear it by 4 mm, the push spread over the arm's skin
// round it so that it leaves no step, a few rounds until nothing crosses.
struct SocketContact {
  static constexpr double kClear = 0.004;  // how far past the trunk's face the arm's skin ends
  static constexpr int kRounds = 8;
  static constexpr int kRings = 8;
  const std::vector<std::vector<int>>* next;  // each vertex's neighbours (one mesh: shared)
  body::Faces near;                           // the faces near the joint
  std::set<std::pair<int, int>> at_rest;      // pairs of `near` that already cross at rest

  SocketContact(const std::vector<Vec3>& P, const std::vector<std::array<int, 3>>& faces,
                const std::vector<std::vector<int>>& neighbours, const Vec3& joint, double reach)
      : next(&neighbours) {
    std::vector<int> picked;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
      const auto& t = faces[f];
      if (((P[t[0]] + P[t[1]] + P[t[2]]) / 3.0 - joint).norm() < reach) picked.push_back(f);
    }
    near.resize(static_cast<Eigen::Index>(picked.size()), 3);
    for (std::size_t i = 0; i < picked.size(); ++i)
      for (int k = 0; k < 3; ++k) near(static_cast<Eigen::Index>(i), k) = faces[picked[i]][k];
    for (const auto& pr : body::intersecting_face_pairs(as_vertices(P), near)) at_rest.insert(pr);
  }

  static body::Vertices as_vertices(const std::vector<Vec3>& X) {
    body::Vertices out(static_cast<Eigen::Index>(X.size()), 3);
    for (std::size_t v = 0; v < X.size(); ++v)
      out.row(static_cast<Eigen::Index>(v)) = X[v].cast<float>().transpose();
    return out;
  }

  // How far each `zone` vertex of the arm's skin in `X` (all vertices, posed) must move for it
  // to clear the trunk's faces it crosses (the vertices moved are in the zone: the shoulder's
  // blend zone and the upper arm near it).
  std::vector<Vec3> press(std::vector<Vec3> X, const Eigen::VectorXd& share,
                          const std::vector<int>& zone) const {
    std::vector<Vec3> moved(zone.size(), Vec3::Zero());
    std::vector<int> where(X.size(), -1);
    for (std::size_t i = 0; i < zone.size(); ++i) where[zone[i]] = static_cast<int>(i);
    const auto face_share = [&](int f) {
      return (share[near(f, 0)] + share[near(f, 1)] + share[near(f, 2)]) / 3.0;
    };
    for (int round = 0; round < kRounds; ++round) {
      std::vector<Vec3> push(X.size(), Vec3::Zero());
      bool any = false;
      for (auto [f, g] : body::intersecting_face_pairs(as_vertices(X), near)) {
        if (at_rest.count({f, g})) continue;
        if (face_share(f) < face_share(g)) std::swap(f, g);
        if (face_share(f) < 0.5 || face_share(f) - face_share(g) < 0.3) continue;
        const Vec3 a = X[near(g, 0)];
        const Vec3 n = (X[near(g, 1)] - a).cross(X[near(g, 2)] - a).normalized();
        for (int k = 0; k < 3; ++k) {
          const int v = static_cast<int>(near(f, k));
          if (where[v] < 0 || share[v] < 0.5) continue;
          const double need = kClear - (X[v] - a).dot(n);
          if (need > push[v].norm()) {
            push[v] = need * n;
            any = true;
          }
        }
      }
      if (!any) break;
      // Spread over kRings rings of the arm's skin (not across the seam) in a tent: a vertex
      // r rings from a pushed one moves (1 - r / (kRings + 1)) as far. Halving each ring over
      // three rings left a dent with ridges round it on the inner arm.
      std::vector<Vec3> seed = push;
      std::vector<int> ring_of(X.size(), 0);
      const auto reach = [](int ring) { return 1.0 - static_cast<double>(ring) / (kRings + 1); };
      for (int ring = 0; ring < kRings; ++ring) {
        std::vector<Vec3> next_seed = seed;
        std::vector<int> next_ring = ring_of;
        for (std::size_t v = 0; v < X.size(); ++v) {
          if (where[v] < 0 || share[v] < 0.5) continue;
          for (int w : (*next)[v]) {
            const double from_w = seed[w].norm() * reach(ring_of[w] + 1);
            if (ring_of[w] < kRings && from_w > next_seed[v].norm() * reach(next_ring[v])) {
              next_seed[v] = seed[w];
              next_ring[v] = ring_of[w] + 1;
            }
          }
        }
        seed.swap(next_seed);
        ring_of.swap(next_ring);
      }
      for (std::size_t v = 0; v < X.size(); ++v) push[v] = reach(ring_of[v]) * seed[v];
      for (std::size_t v = 0; v < X.size(); ++v)
        if (where[v] >= 0 && push[v].squaredNorm() > 0.0) {
          X[v] += push[v];
          moved[where[v]] += push[v];
        }
    }
    return moved;
  }
};

bool is_hinge(int joint) {
  return joint == kLeftElbow || joint == kRightElbow || joint == kLeftKnee || joint == kRightKnee;
}

// The fit of one joint's columns on the rest body P (with the rig's joints at that body's
// joints). The template kind needs the mannequin whose primitives it poses.
JointFit fit_joint(const std::vector<Vec3>& P, const SmplxRig& rig, const Eigen::VectorXd& share,
                   const Eigen::MatrixXd& weights, int joint, PosedTarget kind,
                   const Mannequin* mannequin, const ContactBody& other,
                   const std::vector<std::array<int, 3>>* faces,
                   const std::vector<ContactBody>* socket_bodies) {
  const int V = static_cast<int>(P.size());
  JointFit fit;
  // The hinges' flesh meets beyond their blend zones: the two segments near the joint take
  // correctives too (the parent segment's skin is weighted to the parent joint).
  const bool hinge = kind == PosedTarget::kTemplate && is_hinge(joint);
  const int parent = rig.parents[joint];
  const int child = limb_child(joint);
  const std::vector<Vec3>& C = other.rest ? *other.rest : P;
  const SmplxRig& contact_rig = other.rig ? *other.rig : rig;
  const HingeContact contact(contact_rig, joint, parent, child);
  // The arm's skin near the shoulder takes correctives too, where it meets the trunk.
  const bool socket = kind == PosedTarget::kRotationShare && faces && socket_bodies &&
                      (joint == kLeftShoulder || joint == kRightShoulder);
  // Within 80 % of the upper arm's length of the shoulder, as the hinges' reach.
  const auto arm_reach = [&](const SmplxRig& r) {
    return 0.8 * (r.joints[limb_child(joint)] - r.joints[joint]).norm();
  };
  const double reach_here = arm_reach(rig);
  std::vector<std::vector<int>> neighbours;
  std::vector<SocketContact> trunks;
  if (socket) {
    neighbours = neighbours_by_face(P.size(), *faces);
    for (const ContactBody& b : *socket_bodies)
      trunks.emplace_back(*b.rest, *faces, neighbours, b.rig->joints[joint], arm_reach(*b.rig));
  }
  for (int v = 0; v < V; ++v) {
    const bool blend = share[v] > 0.005 && share[v] < 0.995;
    const bool near_limb = hinge && (C[v] - contact.centre).norm() < contact.reach &&
                           (share[v] >= 0.995 || weights(v, parent) > 0.5);
    const bool near_arm =
        socket && share[v] >= 0.995 && (P[v] - rig.joints[joint]).norm() < reach_here;
    if (blend || near_limb || near_arm) fit.zone.push_back(v);
  }
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
    // Linear blending of rest vertex p about the joint at o, and the rotation share's target.
    const auto skin = [&](const Vec3& p, const Vec3& o, int v) {
      return Vec3((1.0 - share[v]) * p + share[v] * (o + R * (p - o)));
    };
    const auto shared_turn = [&](const Vec3& p, const Vec3& o, int v) {
      const Eigen::AngleAxisd part(share[v] * turn_of.angle(), turn_of.axis());
      return Vec3(o + part.toRotationMatrix() * (p - o));
    };
    std::vector<Vec3> offsets(n, Vec3::Zero()), zone_rest(n);
    std::vector<double> pressed(n, 0.0);
    for (int i = 0; i < n; ++i) {
      const int v = fit.zone[i];
      const Vec3 skinned = skin(P[v], c, v);
      Vec3& r = offsets[i];
      if (kind == PosedTarget::kTemplate) {
        r = mannequin->project(skinned, 8, &pose) - skinned;
        // Farther than 3 cm the projection found another part of the body (the forearm
        // pressed into the biceps): nothing to learn there.
        if (r.norm() > 0.03) r.setZero();
        if (hinge) {
          // Contact on the contact body, the template's offsets elsewhere.
          const Vec3& cc = contact.centre;
          const Vec3 at = (1.0 - share[v]) * C[v] + share[v] * (cc + R * (C[v] - cc));
          r = contact.apply(C[v], at, at + r, R, &pressed[i]) - at;
          zone_rest[i] = C[v];
        }
      } else {
        r = strength * (shared_turn(P[v], c, v) - skinned);
      }
    }
    if (hinge) contact.bulge(zone_rest, pressed, R, offsets);
    if (socket) {
      // The correctives are one set for all bodies: each body in turn (the mean body first, then
      // its +-3 SD bodies) is posed with the moves the bodies before it needed and adds what it
      // still needs. Taking the largest move per vertex over the bodies instead crumpled the
      // mean body's armpit (folds of 179 degrees).
      std::vector<Vec3> moves(n, Vec3::Zero());
      for (std::size_t b = 0; b < trunks.size(); ++b) {
        const std::vector<Vec3>& Q = *(*socket_bodies)[b].rest;
        const Vec3 cb = (*socket_bodies)[b].rig->joints[joint];
        std::vector<Vec3> X(V);
        for (int v = 0; v < V; ++v) X[v] = skin(Q[v], cb, v);
        for (int i = 0; i < n; ++i) {
          const int v = fit.zone[i];
          X[v] += strength * (shared_turn(Q[v], cb, v) - X[v]) + moves[i];
        }
        const std::vector<Vec3> m = trunks[b].press(std::move(X), share, fit.zone);
        for (int i = 0; i < n; ++i) moves[i] += m[i];
      }
      for (int i = 0; i < n; ++i) offsets[i] += moves[i];
    }
    for (int i = 0; i < n; ++i) {
      const int v = fit.zone[i];
      const Eigen::Matrix3d M = (1.0 - share[v]) * Eigen::Matrix3d::Identity() + share[v] * R;
      targets[i].col(s) = M.inverse() * offsets[i];
      fit.skinning_error += offsets[i].norm();
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
                                const Mannequin* mannequin, Eigen::MatrixXf& posedirs,
                                const ContactBody& other = {},
                                const std::vector<std::array<int, 3>>* faces = nullptr,
                                const std::vector<ContactBody>* socket_bodies = nullptr) {
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
        fits[i] = fit_joint(P, rig, share, weights, joints[i], kind, mannequin, other, faces,
                            socket_bodies);
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

void fit_hinge_contact_correctives(const Mannequin& mannequin, const TriMesh& mesh,
                                   const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                   const std::vector<Vec3>& rest, const SmplxRig& rest_rig,
                                   int threads, Eigen::MatrixXf& posedirs) {
  std::vector<int> hinges;
  for (int j : template_joints())
    if (is_hinge(j)) hinges.push_back(j);
  fit_joints(hinges, PosedTarget::kTemplate, mesh.vertices, rig, weights, threads, &mannequin,
             posedirs, ContactBody{&rest, &rest_rig});
}

void fit_rotation_share_correctives(const std::vector<Vec3>& rest,
                                    const std::vector<std::array<int, 3>>& faces,
                                    const std::vector<ContactBody>& contact_bodies,
                                    const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                    int threads, Eigen::MatrixXf& posedirs,
                                    PoseCorrectiveReport* report) {
  const PoseCorrectiveReport shared =
      fit_joints(rotation_share_joints(), PosedTarget::kRotationShare, rest, rig, weights, threads,
                 nullptr, posedirs, {}, &faces, &contact_bodies);
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
