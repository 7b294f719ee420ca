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

struct ExportOptions {
  bool morph_targets = true;  // the shape components as morph targets, betas as weights
  // Binary (.glb) or text (.gltf + embedded buffer) follows the file extension.
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
