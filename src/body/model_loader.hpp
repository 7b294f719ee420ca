// Loading SMPL-family models from .npz files (or bytes in memory), with validation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/npz_reader.hpp"

namespace body {

// Loads and validates a model; a built-in model's name (female, male, neutral) stands for that
// model unless a file of that name exists. Keeps the first `components` shape components (all if
// the file has fewer; 0 = all) and, for SMPL-X, the first `expressions` expression components
// (kept apart from the shape components, see Model::expression_dirs). Throws ModelError naming
// the file, the array and the problem.
Model load_model(const std::filesystem::path& path, int components = 10, int expressions = 0);

// The same from an in-memory .npz; `label` stands in for the file name in messages.
Model load_model_from_memory(const void* data, std::size_t size, const std::string& label,
                             int components = 10, int expressions = 0);

// Reads the optional pose correctives (`posedirs`) of a model loaded from a file, for posing
// (a T-pose export). Not part of load_model because they are large (SMPL-X: 486 columns, as
// big as its shape space) and only posing needs them. Does nothing if the model already has
// them, or did not come from a file; throws ModelError if the array is malformed.
void load_pose_correctives(Model& model);

// What `inspect` reports on a model (a built-in name or a file, as resolve_model takes it):
// the model with its first shape component only, after checking every value of all its shape
// and expression components and of its pose correctives (what load_pose_correctives would
// read), none of which are kept; `pose_columns` is posedirs' column count (0: none). A check
// costs one pass over the file's bytes and the memory of the kept arrays. Throws ModelError as
// load_model does.
struct ModelCheck {
  Model model;
  int pose_columns = 0;
};
ModelCheck check_model(const std::string& name_or_path);

// The built-in body models (assets/body_{female,male,neutral}.npz compiled into the binary):
// their names, in the order female, male, neutral.
const std::vector<std::string>& builtin_model_names();
bool is_builtin_model_name(const std::string& name);
// Throws ModelError for an unknown name, or if the models were not built in.
NpzArchive open_builtin_model_archive(const std::string& name);
Model load_builtin_model(const std::string& name, int components = 10);

// What a --model argument or a model picker chooses: "female", "male" or "neutral" (built in),
// otherwise a file path; empty = the default (neutral).
Model resolve_model(const std::string& name_or_path, int components = 10);

// The default body model: the built-in neutral model.
Model load_default_model(int components = 10);

}  // namespace body
