// Loading SMPL-family models from .npz files (or bytes in memory), with validation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "body/body_model.hpp"

namespace body {

// Loads and validates a model; keeps the first `components` shape components (all if the file
// has fewer; 0 = all) and, for SMPL-X, the first `expressions` expression components (kept
// apart from the shape components, see Model::expression_dirs). Throws ModelError naming the
// file, the array and the problem.
Model load_model(const std::filesystem::path& path, int components = 10, int expressions = 0);

// The same from an in-memory .npz; `label` stands in for the file name in messages.
Model load_model_from_memory(const void* data, std::size_t size, const std::string& label,
                             int components = 10, int expressions = 0);

// Reads the optional pose correctives (`posedirs`) of a model loaded from a file, for posing
// (a T-pose export). Not part of load_model because they are large (SMPL-X: 486 columns, as
// big as its shape space) and only posing needs them. Does nothing if the model already has
// them, or did not come from a file; throws ModelError if the array is malformed.
void load_pose_correctives(Model& model);

// The embedded default body model (assets/default_body.npz compiled into the binary).
Model load_default_model(int components = 10);

}  // namespace body
