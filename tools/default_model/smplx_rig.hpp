// The rig the default models are exported with: SMPL-X's 55 joints (SMPL's first 22, the jaw,
// the two eyes and three joints per finger, SMPL-X's names and order), skin weights from bone
// heat diffusion (Baran & Popovic 2007, "Automatic rigging and animation of 3D characters")
// and a joint regressor for every joint. The shape deformation keeps its own 24-joint skeleton
// (mannequin_shape.hpp); the first 22 joints of both are the same.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "implicit_mesher.hpp"
#include "mannequin_shape.hpp"

namespace default_model {

// SMPL-X's finger joints: kSmplxHandsBegin + 15 side + 3 finger + k (side 0 = left; fingers in
// SMPL-X's order index, middle, pinky, ring, thumb; k = 0 at the knuckle).
constexpr int kSmplxHandsBegin = 25;
constexpr int kSmplxJoints = kSmplxHandsBegin + 30;

struct Segment {
  Vec3 a, b;
  double radius = 0.05;  // the limb's typical radius round it: distances are compared in radii
};

struct SmplxRig {
  std::vector<std::string> names;
  std::vector<int> parents;  // -1 for the root
  std::vector<Vec3> joints;  // rest positions on the template
  // The segments each joint moves: heat sources for the skin weights (may be empty).
  std::vector<std::vector<Segment>> segments;
  std::array<int, 2> eyes{};  // the eye joints (left, right): their eyeballs move rigidly
  int jaw = -1, head = -1;
  RigLandmarks landmarks;

  int size() const { return static_cast<int>(names.size()); }
};

SmplxRig smplx_rig(const Mannequin& mannequin);

struct HeatWeightReport {
  int vertices_without_visible_bone = 0;  // they take their weights from their neighbours
  int eyeball_vertices = 0;
};

// V x J skin weights: for each joint j, w_j solves (L + A H) w_j = A H p_j on the template
// (L the cotangent Laplacian with its negative weights clamped to 0, so weights stay in [0, 1];
// A the vertex areas; H = 1 / d^2 with d the distance to the nearest bone segment that the
// vertex sees through the inside of the body, `inside` < 0 there; p_j = 1 where that bone is
// j's). Nearest in units of each segment's radius: measured in metres, the chest's sides and
// the lower belly lie nearer the thin arm and thigh bones than the trunk's, and went with them.
// Then at most `max_influences` per vertex (the largest), rows renormalised to 1; the jaw's weight
// above the mouth line goes to the head, eyeballs follow their eye alone.
Eigen::MatrixXd heat_weights(const TriMesh& mesh, const SmplxRig& rig,
                             const std::function<double(const Vec3&)>& inside, int max_influences,
                             HeatWeightReport* report = nullptr);

// J x V regressor: rows 0..21 are `body_rows` (the shape model's own regressor, so the
// measurements see the same joints); the others are convex combinations of the vertices that
// the joint or its parent mostly moves (by `weights`), tilted to reproduce the joint on the
// template (maximum entropy, as rig.hpp's joint_regressor). `fit_error` (optional): the largest
// distance between a regressed and a rest joint.
Eigen::MatrixXd smplx_regressor(const TriMesh& mesh, const SmplxRig& rig,
                                const Eigen::MatrixXd& body_rows, const Eigen::MatrixXd& weights,
                                double* fit_error = nullptr);

}  // namespace default_model
