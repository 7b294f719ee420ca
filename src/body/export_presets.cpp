#include "body/export_presets.hpp"

namespace body {

namespace {

ExportPreset make(const char* name, const char* ext, const char* description, RestPose pose,
                  MorphEncoding morph, JointNaming naming) {
  ExportPreset p;
  p.name = name;
  p.extension = ext;
  p.description = description;
  p.options.rest_pose = pose;
  p.options.morph_encoding = morph;
  p.options.joint_naming = naming;
  return p;
}

}  // namespace

const std::vector<ExportPreset>& export_presets() {
  static const std::vector<ExportPreset> presets = {
      make("blender", ".glb", "model's own rest pose, +-3 sigma shape keys (0..1), SMPL names",
           RestPose::model, MorphEncoding::split_signed, JointNaming::model),
      make("unity", ".glb", "T-pose, humanoid bone names (hips, leftUpperArm, ...), +-3 sigma",
           RestPose::t, MorphEncoding::split_signed, JointNaming::humanoid),
      make("unreal", ".glb",
           "T-pose (retargeting base pose), UE5 mannequin bone names (pelvis, thigh_l, ...), "
           "+-3 sigma",
           RestPose::t, MorphEncoding::split_signed, JointNaming::unreal),
      make("threejs", ".glb", "model's own rest pose, one target per component (w = d beta)",
           RestPose::model, MorphEncoding::betas, JointNaming::model),
      make("vrm", ".vrm", "VRM 1.0 avatar: T-pose, VRMC_vrm humanoid map and meta, +-3 sigma",
           RestPose::t, MorphEncoding::split_signed, JointNaming::model),
  };
  return presets;
}

std::optional<ExportPreset> find_export_preset(const std::string& name) {
  for (const auto& p : export_presets()) {
    if (p.name == name) return p;
  }
  return std::nullopt;
}

}  // namespace body
