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

}  // namespace body
