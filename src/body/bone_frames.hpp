// Rest-pose orientations for the exported skeleton: each joint's local +Y axis points at its
// chosen child, which is where Blender's glTF importer (default "Blender" bone heuristic) and
// most rigging tools put the bone's tail.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

// Index of the child a joint's bone points at, or -1 for a leaf. With several children the
// one on the body's centre line wins (pelvis -> spine1, spine3 -> neck), then a middle finger
// (wrist -> middle1), then the child with the most descendants, then the first.
std::vector<int> bone_targets(const std::vector<int>& parents,
                              const std::vector<std::string>& names);

// World rotation of each joint's rest frame: +Y from the joint to its target child (leaves
// continue their parent's direction), the roll chosen so that +Z lies as close to the body's
// front (+Z world) as the bone allows (bones along z use +X world for the roll instead).
std::vector<Eigen::Matrix3f> bone_frames(const std::vector<int>& parents,
                                         const std::vector<std::string>& names,
                                         const Vertices& joints);

}  // namespace body
