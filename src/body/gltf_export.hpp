// glTF 2.0 / VRM 1.0 export of one body (metres, y up, facing +Z, feet on the ground,
// rig-ready skeleton). No GL here.
//
// What the file holds (the meaning of the weights, for users and other tools):
// - The base mesh is the designed body, in the chosen rest pose: with every morph weight at 0
//   (the default) the mesh is the design and matches the skeleton exactly.
// - The morph targets (kept so the body stays editable) are changes of the design, never a
//   second copy of it: "shape_NN_pos" at weight w adds 3w to shape coefficient NN (w = 1 is
//   +3 standard deviations), "shape_NN_neg" subtracts 3w; with MorphEncoding::betas one target
//   "shape_NN" per component adds w. "expr_NN" (SMPL-X, only when expressions were loaded)
//   adds w to expression coefficient NN. Bones stay where the design put them: large edits
//   through the weights drift away from the skeleton, as in every client.
// - Each joint's rest rotation points its local +Y axis at its child (bone_frames.hpp); the
//   inverse bind matrices match.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "body/body_model.hpp"

namespace body {

class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How shape components become morph targets (shape keys).
enum class MorphEncoding {
  // Two targets per component, "shape_NN_pos" = +3 sigma and "shape_NN_neg" = -3 sigma: every
  // useful weight lies in [0, 1]. The default, because Blender's glTF importer clamps negative
  // shape-key values to 0 (KhronosGroup/glTF-Blender-IO issue #1364) and Unity's blend shape
  // sliders start at 0.
  split_signed,
  // One target per component ("shape_NN" = +1 sigma), weight = change of beta (may be < 0).
  betas,
};

enum class RestPose {
  automatic,  // T for .vrm (VRM 1.0 requires it), else the model's own (A for the default model)
  model,      // the model's own rest pose ("a" on the command line)
  t,          // arms horizontal, posed by the model's linear blend skinning (posing.hpp)
};

// Bone names in the file.
enum class JointNaming {
  model,     // the model's names (SMPL-family names built in, body/joint_names.hpp)
  humanoid,  // VRM humanoid names ("leftUpperArm"; body::humanoid_bone_name), which Unity's
             // Humanoid avatar and most retargeting tools map automatically
  unreal,    // the UE5 mannequin's names ("thigh_l"; body::unreal_bone_name), which Unreal's
             // IK Retargeter maps to its mannequin
};

// VRM 1.0 `meta` (VRMC_vrm). Defaults: a personal, non-profit licence that allows nothing
// beyond the author's own use; the user sets what they mean to grant.
struct VrmMeta {
  std::string name;  // empty: the model's name
  std::string version = "1.0";
  std::vector<std::string> authors;  // empty: "unknown"
  std::string license_url = "https://vrm.dev/licenses/1.0/";
  std::string avatar_permission = "onlyAuthor";  // onlyAuthor|onlySeparatelyLicensedPerson|everyone
  std::string commercial_usage = "personalNonProfit";  // |personalProfit|corporation
  std::string credit_notation = "required";            // |unnecessary
  std::string modification = "prohibited";  // |allowModification|allowModificationRedistribution
  bool allow_redistribution = false;
};

// Everything a caller (the export command, the window's save dialog) can choose; presets
// (export_presets.hpp) fill it for the usual destinations. For a T-pose with the model's pose
// correctives call load_pose_correctives(model) (model_loader.hpp) first: the loader leaves
// them out because only posing needs them.
struct ExportOptions {
  bool morph_targets = true;  // the shape components as morph targets (else shape only baked)
  MorphEncoding morph_encoding = MorphEncoding::split_signed;
  RestPose rest_pose = RestPose::automatic;
  JointNaming joint_naming = JointNaming::model;
  VrmMeta vrm;  // used for .vrm files
  // The file type follows the extension: .glb (binary), .gltf (JSON, embedded buffer), .vrm
  // (binary glTF with VRMC_vrm, always T-pose).
};

// Writes atomically (temporary file, then rename): on any failure the previous file at `path`
// is untouched and ExportError names the file and the reason (e.g. disk full).
void export_gltf(const Model& model, const Eigen::VectorXf& betas,
                 const std::filesystem::path& path, const ExportOptions& options = {});

// How many morph targets an export of `model` with `options` writes (shape and expression
// targets), so a caller can warn before writing a very large file.
int morph_target_count(const Model& model, const ExportOptions& options);

// Above this many morph targets files get large (tens of megabytes or more) and some tools
// load them slowly: callers warn first.
constexpr int kManyMorphTargets = 200;

enum class FileKind { glb, gltf, vrm };

// The same document as bytes. Throws ExportError on invalid betas or a skeleton the chosen
// options cannot use (a T-pose or VRM without SMPL-family arm joints).
std::string export_gltf_bytes(const Model& model, const Eigen::VectorXf& betas, FileKind kind,
                              const ExportOptions& options = {});
inline std::string export_gltf_bytes(const Model& model, const Eigen::VectorXf& betas, bool binary,
                                     const ExportOptions& options = {}) {
  return export_gltf_bytes(model, betas, binary ? FileKind::glb : FileKind::gltf, options);
}

}  // namespace body
