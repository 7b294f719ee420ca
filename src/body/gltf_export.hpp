// glTF 2.0 export of one body (metres, y up, feet on the ground, rig-ready skeleton).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "body/body_model.hpp"

namespace body {

class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How shape components become morph targets (shape keys).
enum class MorphEncoding {
  // Two targets per component, "shape_NN_pos" = +3 sigma and "shape_NN_neg" = -3 sigma, with
  // weights max(+-beta, 0) / 3: every weight lies in [0, 1] for |beta| <= 3. The default,
  // because Blender's glTF importer clamps negative shape-key values to 0
  // (KhronosGroup/glTF-Blender-IO issue #1364), which would silently change the body.
  split_signed,
  // One target per component ("shape_NN" = the component) with weight = beta (may be < 0).
  betas,
};

struct ExportOptions {
  bool morph_targets = true;  // the shape components as morph targets (else the shape is baked)
  MorphEncoding morph_encoding = MorphEncoding::split_signed;
  // Binary (.glb) or text (.gltf + embedded buffer) follows the file extension. Either way the
  // base mesh is the model's template (mean body) and the default weights give the chosen
  // body; without morph targets the base mesh is the chosen body.
};

// Writes atomically (temporary file, then rename): on any failure the previous file at `path`
// is untouched and ExportError names the file and the reason (e.g. disk full).
void export_gltf(const Model& model, const Eigen::VectorXf& betas,
                 const std::filesystem::path& path, const ExportOptions& options = {});

// The same document as bytes: binary .glb (binary = true) or .gltf JSON with the buffer
// embedded as a data URI. Throws ExportError on invalid betas.
std::string export_gltf_bytes(const Model& model, const Eigen::VectorXf& betas, bool binary,
                              const ExportOptions& options = {});

}  // namespace body
