// Joint names of the SMPL family (built in, so files without a `joint_names` array still get
// meaningful bone names) and the VRM 1.0 humanoid bone each SMPL-family joint plays.
#pragma once

#include <string>
#include <vector>

namespace body {

// SMPL's 24 standard joint names, in SMPL's joint order (STAR uses the same skeleton).
const std::vector<std::string>& smpl_joint_names();

// The names for a model with J joints when J identifies an SMPL-family skeleton: 24 (SMPL,
// STAR), 52 (SMPL+H), 55 (SMPL-X); nullptr for any other count.
const std::vector<std::string>* builtin_joint_names(std::size_t joints);

// The VRM 1.0 humanoid bone name ("hips", "leftUpperArm", ...) of an SMPL-family joint name,
// or "" when the joint has no humanoid role (e.g. SMPL's hand end joints).
std::string vrm_humanoid_bone(const std::string& joint_name);

// A bone name in the humanoid style for every SMPL-family joint: its VRM humanoid bone, and
// for the joints without a role the same style ("leftHandEnd" for SMPL's left_hand, the end
// of the hand beyond the wrist), so that no SMPL name is left among humanoid ones. "" for a
// name that is not an SMPL-family joint.
std::string humanoid_bone_name(const std::string& joint_name);

// The Unreal Engine 5 mannequin's bone name of an SMPL-family joint (pelvis, spine_01,
// thigh_l, calf_l, foot_l, ball_l, clavicle_l, upperarm_l, lowerarm_l, hand_l, index_01_l,
// ..., thumb_03_l, neck_01, head: the names Epic documents for its mannequin skeleton), and
// names in the same style for the joints the mannequin lacks (hand_end_l for SMPL's hand end,
// jaw, eye_l, eye_r). "" for a name that is not an SMPL-family joint.
std::string unreal_bone_name(const std::string& joint_name);

}  // namespace body
