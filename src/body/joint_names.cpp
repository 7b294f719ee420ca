// Joint orders from the models' public documentation (SMPL: Loper et al. 2015; SMPL+H: Romero
// et al. 2017; SMPL-X: Pavlakos et al. 2019, as listed by the `smplx` package's joint names):
// SMPL+H and SMPL-X keep SMPL's first 22 joints (pelvis ... right_wrist); SMPL+H then has the
// left hand's 15 joints and the right hand's 15; SMPL-X has jaw and the two eyes first.
#include "body/joint_names.hpp"

#include <map>

namespace body {

namespace {

std::vector<std::string> hand(const std::string& side) {
  std::vector<std::string> out;
  for (const char* finger : {"index", "middle", "pinky", "ring", "thumb"}) {
    for (int k = 1; k <= 3; ++k) out.push_back(side + "_" + finger + std::to_string(k));
  }
  return out;
}

std::vector<std::string> body22() {
  const auto& s = smpl_joint_names();
  return {s.begin(), s.begin() + 22};
}

}  // namespace

const std::vector<std::string>& smpl_joint_names() {
  static const std::vector<std::string> names = {
      "pelvis",     "left_hip",    "right_hip",    "spine1",      "left_knee",     "right_knee",
      "spine2",     "left_ankle",  "right_ankle",  "spine3",      "left_foot",     "right_foot",
      "neck",       "left_collar", "right_collar", "head",        "left_shoulder", "right_shoulder",
      "left_elbow", "right_elbow", "left_wrist",   "right_wrist", "left_hand",     "right_hand"};
  return names;
}

const std::vector<std::string>* builtin_joint_names(std::size_t joints) {
  static const std::vector<std::string> smplh = [] {
    auto n = body22();
    for (const auto& side : {"left", "right"}) {
      const auto h = hand(side);
      n.insert(n.end(), h.begin(), h.end());
    }
    return n;
  }();
  static const std::vector<std::string> smplx = [] {
    auto n = body22();
    n.insert(n.end(), {"jaw", "left_eye_smplhf", "right_eye_smplhf"});
    for (const auto& side : {"left", "right"}) {
      const auto h = hand(side);
      n.insert(n.end(), h.begin(), h.end());
    }
    return n;
  }();
  switch (joints) {
    case 24:
      return &smpl_joint_names();
    case 52:
      return &smplh;
    case 55:
      return &smplx;
    default:
      return nullptr;
  }
}

std::string vrm_humanoid_bone(const std::string& joint_name) {
  static const std::map<std::string, std::string> table = [] {
    std::map<std::string, std::string> t = {{"pelvis", "hips"},
                                            {"spine1", "spine"},
                                            {"spine2", "chest"},
                                            {"spine3", "upperChest"},
                                            {"neck", "neck"},
                                            {"head", "head"},
                                            {"jaw", "jaw"},
                                            {"left_eye_smplhf", "leftEye"},
                                            {"right_eye_smplhf", "rightEye"}};
    const std::pair<const char*, const char*> sided[] = {{"hip", "UpperLeg"},
                                                         {"knee", "LowerLeg"},
                                                         {"ankle", "Foot"},
                                                         {"foot", "Toes"},
                                                         {"collar", "Shoulder"},
                                                         {"shoulder", "UpperArm"},
                                                         {"elbow", "LowerArm"},
                                                         {"wrist", "Hand"},
                                                         {"index1", "IndexProximal"},
                                                         {"index2", "IndexIntermediate"},
                                                         {"index3", "IndexDistal"},
                                                         {"middle1", "MiddleProximal"},
                                                         {"middle2", "MiddleIntermediate"},
                                                         {"middle3", "MiddleDistal"},
                                                         {"ring1", "RingProximal"},
                                                         {"ring2", "RingIntermediate"},
                                                         {"ring3", "RingDistal"},
                                                         {"pinky1", "LittleProximal"},
                                                         {"pinky2", "LittleIntermediate"},
                                                         {"pinky3", "LittleDistal"},
                                                         {"thumb1", "ThumbMetacarpal"},
                                                         {"thumb2", "ThumbProximal"},
                                                         {"thumb3", "ThumbDistal"}};
    for (const auto& [smpl, vrm] : sided) {
      t[std::string("left_") + smpl] = std::string("left") + vrm;
      t[std::string("right_") + smpl] = std::string("right") + vrm;
    }
    return t;
  }();
  const auto it = table.find(joint_name);
  return it == table.end() ? std::string() : it->second;
}

std::string humanoid_bone_name(const std::string& joint_name) {
  if (std::string role = vrm_humanoid_bone(joint_name); !role.empty()) return role;
  if (joint_name == "left_hand") return "leftHandEnd";
  if (joint_name == "right_hand") return "rightHandEnd";
  return {};
}

std::string unreal_bone_name(const std::string& joint_name) {
  static const std::map<std::string, std::string> table = [] {
    std::map<std::string, std::string> t = {
        {"pelvis", "pelvis"},   {"spine1", "spine_01"},       {"spine2", "spine_02"},
        {"spine3", "spine_03"}, {"neck", "neck_01"},          {"head", "head"},
        {"jaw", "jaw"},         {"left_eye_smplhf", "eye_l"}, {"right_eye_smplhf", "eye_r"}};
    const std::pair<const char*, const char*> sided[] = {
        {"hip", "thigh"},         {"knee", "calf"},         {"ankle", "foot"},
        {"foot", "ball"},         {"collar", "clavicle"},   {"shoulder", "upperarm"},
        {"elbow", "lowerarm"},    {"wrist", "hand"},        {"hand", "hand_end"},
        {"index1", "index_01"},   {"index2", "index_02"},   {"index3", "index_03"},
        {"middle1", "middle_01"}, {"middle2", "middle_02"}, {"middle3", "middle_03"},
        {"ring1", "ring_01"},     {"ring2", "ring_02"},     {"ring3", "ring_03"},
        {"pinky1", "pinky_01"},   {"pinky2", "pinky_02"},   {"pinky3", "pinky_03"},
        {"thumb1", "thumb_01"},   {"thumb2", "thumb_02"},   {"thumb3", "thumb_03"}};
    for (const auto& [smpl, ue] : sided) {
      t[std::string("left_") + smpl] = std::string(ue) + "_l";
      t[std::string("right_") + smpl] = std::string(ue) + "_r";
    }
    return t;
  }();
  const auto it = table.find(joint_name);
  return it == table.end() ? std::string() : it->second;
}

}  // namespace body
