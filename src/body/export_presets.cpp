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
      make("blender", ".glb",
           "the model's own rest pose, +-3 sigma shape keys (0..1, Blender clamps negative "
           "values), SMPL joint names",
           RestPose::model, MorphEncoding::split_signed, JointNaming::model),
      make("unity", ".glb",
           "T-pose and humanoid bone names (Humanoid avatar maps itself), +-3 sigma blend "
           "shapes (0..1)",
           RestPose::t, MorphEncoding::split_signed, JointNaming::humanoid),
      make("unreal", ".glb",
           "T-pose (retargeting base pose), humanoid bone names, +-3 sigma morph targets "
           "(0..1)",
           RestPose::t, MorphEncoding::split_signed, JointNaming::humanoid),
      make("threejs", ".glb",
           "the model's own rest pose, one morph target per component (influence = change "
           "of beta, may be negative), SMPL joint names",
           RestPose::model, MorphEncoding::betas, JointNaming::model),
      make("vrm", ".vrm",
           "VRM 1.0 avatar: T-pose, VRMC_vrm humanoid map and meta, +-3 sigma morph targets",
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
