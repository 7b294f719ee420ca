// Named export settings for the usual destinations (`export --preset`, the save dialog).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "body/gltf_export.hpp"

namespace body {

struct ExportPreset {
  std::string name;         // "blender", "unity", ...
  std::string extension;    // the file type it suggests: ".glb" or ".vrm"
  std::string description;  // one short line (<= 66 characters) for --help and the dialog
  ExportOptions options;
};

const std::vector<ExportPreset>& export_presets();

// The preset of that name, or nullopt.
std::optional<ExportPreset> find_export_preset(const std::string& name);

}  // namespace body
