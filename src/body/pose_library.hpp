// Named test poses for skinned body models (the pose benchmark, `bench-pose`, and
// `render --pose`): each pose is a set of local joint rotations built from the model's own rest
// joints, found by joint NAME, so SMPL's 24-joint skeleton and SMPL-X's 55 both work. No GL here.
//
// Frame: metres, y up, the body faces +z, the subject's left on +x. Both sides are posed
// symmetrically; the figures of the benchmark are taken on the left side.
#pragma once

#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/pose_quality.hpp"
#include "body/posing.hpp"

namespace body {

enum class PoseKind {
  kShoulderAbduct,  // upper arm at `degrees` from hanging straight down, in the frontal plane
  kShoulderFlex,    // upper arm at `degrees` from hanging, in the sagittal plane, forward
  kElbowFlex,       // forearm toward the front about the normal of upper arm and forward
  kForearmTwist,    // at the elbow about the forearm's axis (pronation)
  kWristFlex,       // hand toward the palm
  kHipFlex,         // thigh at `degrees` from hanging, forward
  kKneeFlex,        // shin backward about the normal of thigh and forward
  kHeadTurn,        // head about the vertical at the head joint, face toward the left (+x)
  kFist,            // every finger joint toward the palm, the thumb across it
};

struct PoseDefinition {
  std::string name;         // e.g. "shoulder-abduct-170-from-t"
  std::string description;  // one line for tables and --help
  PoseKind kind;
  double degrees;
  // The rest for this pose is the T-pose (t_posed): its mesh and joints, the same weights, as a
  // T-pose glTF export gives an engine; otherwise the model's own rest pose.
  bool from_t = false;
  // Faces of the hands may touch each other in this pose (the fist); the benchmark does not
  // count intersections among them.
  bool hand_contact = false;
};

// The benchmark's poses in table order: shoulder-abduct-80, -170, the same -from-t,
// shoulder-flex-90, elbow-130, forearm-twist-90, wrist-flex-60, hip-flex-90, knee-130,
// head-turn-60, fist.
const std::vector<PoseDefinition>& pose_library();
// nullptr for an unknown name.
const PoseDefinition* find_pose(const std::string& name);
// "shoulder-abduct-80, shoulder-abduct-170, ..." for messages.
std::string pose_names();

// Local rotations of a pose for a skeleton, or why the model cannot make it (e.g. a fist
// without finger joints): that is a property of the model, not an error.
struct PoseRotations {
  bool available = false;
  std::string reason;  // when not available: what the skeleton lacks
  Rotations local;     // one per joint (identity where the pose leaves a joint alone)
};

// `rest_joints` (J x 3) are the joints of the rest the pose starts from (the model's own or,
// for from_t poses, the T-posed joints); every global rotation is identity there, so rest
// directions read directly off the joint positions.
PoseRotations pose_rotations(const Model& model, const Vertices& rest_joints,
                             const PoseDefinition& pose);

// The left-side joints a pose is measured at (the posed joint; for the fist every left finger
// joint), each with the radius of its region: a fixed share of a bone next to it, so that it
// scales with the body. From the rest joints; empty when the model lacks them.
std::vector<JointRegion> measured_joints(const Model& model, const Vertices& rest_joints,
                                         const PoseDefinition& pose);

// Joints of both hands (wrists, SMPL's hand end joints, finger joints): faces mostly weighted
// to them are the fist's own faces.
std::vector<int> hand_joints(const Model& model);

// A body in a test pose: the rest it starts from and the posed mesh.
struct PosedBody {
  bool available = false;
  std::string reason;
  Vertices rest_vertices;  // the model's rest or the T-posed mesh (from_t), not grounded
  Vertices rest_joints;
  Vertices posed_vertices;
  Vertices posed_joints;
  Rotations local;
  bool correctives_applied = false;  // SMPL-layout posedirs used (for the pose, or the T-pose)
};

// Poses `shaped` (evaluate()'s mesh of the model's rest) with the model's linear blend
// skinning: for the model's own rest with its pose correctives when the file has them in SMPL's
// layout; for from_t poses the T-posed mesh (with correctives, as t_posed makes it) is the
// rest and the pose is skinned from it without further correctives, as an engine skins a T-pose
// export. The model stays as it is; nothing is grounded.
PosedBody pose_body(const Model& model, const BodyMesh& shaped, const PoseDefinition& pose);

}  // namespace body
