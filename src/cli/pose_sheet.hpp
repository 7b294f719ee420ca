// The pose benchmark's contact sheet: every pose of a model's mean body in one labelled PNG.
// The drawing needs the GL renderer, which a build without SG_BUILD_GUI lacks; so
// `bench-pose` (always built) reaches it through this hook, which render_pose_sheet.cpp (built
// with the renderer) fills in at start-up.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "body/body_model.hpp"

namespace cli {

struct PoseSheetCell {
  std::string pose;                // pose name: chooses the framing
  bool available = false;          // false: an empty cell saying so
  body::BodyMesh mesh;             // posed, feet on the ground, with normals
  std::vector<std::string> label;  // lines under the cell
};

struct PoseSheetBlock {
  std::string title;  // e.g. "female: mean body"
  const body::Model* model = nullptr;
  std::vector<PoseSheetCell> cells;
};

// Writes the sheet (4 cells a row, `cell_px` square cells, blocks one under the other)
// atomically to `path`; throws std::runtime_error naming the file or the renderer's problem.
using PoseSheetWriter = void (*)(const std::filesystem::path& path,
                                 const std::vector<PoseSheetBlock>& blocks, int cell_px);

// nullptr in a build without the renderer.
PoseSheetWriter& pose_sheet_writer();

}  // namespace cli
