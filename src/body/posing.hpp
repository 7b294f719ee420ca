// Posing a body with the model's own linear blend skinning (SMPL's formulation): joint
// rotations relative to the rest pose, pose correctives from `posedirs` when the file has them
// in SMPL's layout. Used to export a T-pose; no GL here.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

using Rotations = std::vector<Eigen::Matrix3f>;  // one per joint, identity = rest

// Linear blend skinning with fixed joint rotations. Because the rotations do not depend on the
// shape, posing is affine in (vertices, joints): the same map takes shape displacements (a
// morph target's field and the joints' displacement) to posed displacements exactly.
class Skinning {
 public:
  // `local` holds each joint's rotation relative to its parent (J entries).
  Skinning(const Model& model, const Rotations& local);

  // Posed vertices of rest-pose vertices `v` (V x 3) on a skeleton with rest joints `joints`
  // (J x 3); also works on displacements (dv, dj).
  Vertices vertices(const Vertices& v, const Vertices& joints) const;
  // Posed joint positions.
  Vertices joints(const Vertices& joints) const;

  const Rotations& global_rotations() const { return global_; }

 private:
  Eigen::MatrixXf translations(const Vertices& joints) const;  // J x 3: t_j of each joint

  const Model& model_;
  std::vector<int> order_;  // parents before children
  Rotations global_;
  Eigen::Matrix<float, Eigen::Dynamic, 9, Eigen::RowMajor> blended_;  // V x 9: sum_j w R_j
};

// SMPL-layout pose correctives for the rotations (3V flat offsets, row 3v + axis), or an empty
// vector when the model has no `posedirs` or they are not in SMPL's 9 (J - 1) layout.
Eigen::VectorXf pose_correctives(const Model& model, const Rotations& local);

// Local rotations that bring the arms horizontal and straight out to the sides (a T-pose):
// each shoulder turns its upper arm onto the horizontal outward axis, each elbow then turns
// its forearm onto the same axis (the smallest rotations that do so, so the arms do not twist).
// Needs joints named left_/right_ shoulder, elbow, wrist; throws ModelError otherwise.
Rotations t_pose_rotations(const Model& model, const Vertices& rest_joints);

// The body in a T-pose: vertices and joints posed by the model's skinning with its pose
// correctives (when in SMPL's layout), normals recomputed, feet on the ground.
// `correctives_applied` (optional) says whether posedirs were used.
BodyMesh t_posed(const Model& model, const BodyMesh& shaped, bool* correctives_applied = nullptr);

// The smallest rotation taking unit vector a onto unit vector b.
Eigen::Matrix3f rotation_between(const Eigen::Vector3f& a, const Eigen::Vector3f& b);

}  // namespace body
