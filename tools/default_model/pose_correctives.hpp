// Pose correctives in SMPL's `posedirs` layout for the default models' rig, fitted to posed
// templates (and, where the template cannot be posed, to rotation-shared skinning). The template is
// a union of primitives that follow the bones (mannequin_shape.hpp), so the generator can pose the
// template itself: turn the primitives after a joint about it and the union keeps its shape (an
// elbow bends round its capsules instead of collapsing, a twisted forearm stays round). For each
// limb joint, the template posed by its skin weights (linear blend skinning) in a set of rotations
// of that joint alone is projected onto that posed surface; the differences, taken back to the rest
// pose through each vertex's blended transform, are fitted linearly in the joint's (R - I) entries
// as SMPL's posedirs are: offset(v) = sum_j P_vj vec(R_j - I), 9 columns per joint after the root.
#pragma once

#include <string>

#include <Eigen/Core>

#include "implicit_mesher.hpp"
#include "mannequin_shape.hpp"
#include "smplx_rig.hpp"

namespace default_model {

// A body of the template's topology other than the template (a model's mean body, one of its
// +-3 SD bodies), with the rig's joints at its own joints: where flesh meets is found on it.
struct ContactBody {
  const std::vector<Vec3>* rest = nullptr;
  const SmplxRig* rig = nullptr;
};

struct PoseCorrectiveReport {
  int joints = 0;                 // joints with correctives
  int poses = 0;                  // posed templates fitted
  double skinning_error_mm = 0;   // mean |skinned - posed template| in the blend zones
  double fitted_error_mm = 0;     // mean |skinned with correctives - posed template|, the same
  int rotation_share_joints = 0;  // joints whose correctives keep the distance from the joint
  int rotation_share_poses = 0;
  std::string describe() const;
};

// 3V x 9 (J - 1), row 3v + axis, column 9 (j - 1) + 3 r + c for entry (r, c) of R_j - I. The
// elbows, knees and ankles get correctives fitted to the posed template; every other column is
// 0 until fit_rotation_share_correctives() fills the shoulders', hips', head's and fingers'.
Eigen::MatrixXf fit_pose_correctives(const Mannequin& mannequin, const TriMesh& mesh,
                                     const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                     int threads, PoseCorrectiveReport* report = nullptr);

// Re-fits the elbows' and knees' columns as fit_pose_correctives does, with the flesh that
// meets in a deep bend found on `rest` (a model's mean body of the template's topology, with
// `rest_rig`'s joints at its joints) instead of the template: a model's limbs are thicker than
// the template's, and pressed by the template's offsets they still went through each other.
void fit_hinge_contact_correctives(const Mannequin& mannequin, const TriMesh& mesh,
                                   const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                   const std::vector<Vec3>& rest, const SmplxRig& rest_rig,
                                   int threads, Eigen::MatrixXf& posedirs);

// Fits the shoulders', hips', head's and finger joints' columns of `posedirs` on a rest body of
// the template's topology (a model's mean body, with `rig`'s joints at that body's joints): each
// blend-zone vertex turned by its share of the rotation. Their offsets are a share of each vertex's
// distance from the joint, so they are fitted per model (slimmer arms than the template's need
// smaller ones). At the shoulders the arm's skin is also kept off the trunk where the two meet
// (an arm raised forward onto the pectoral), on each of `contact_bodies` (the mean body first,
// then the bodies whose contact it must also cover). Adds their counts to `report`.
void fit_rotation_share_correctives(const std::vector<Vec3>& rest,
                                    const std::vector<std::array<int, 3>>& faces,
                                    const std::vector<ContactBody>& contact_bodies,
                                    const SmplxRig& rig, const Eigen::MatrixXd& weights,
                                    int threads, Eigen::MatrixXf& posedirs,
                                    PoseCorrectiveReport* report = nullptr);

}  // namespace default_model
