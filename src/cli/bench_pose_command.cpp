// `bench-pose`: the pose benchmark of skinned body models (body/pose_benchmark.hpp). Prints a
// markdown report, writes it to --out, and draws the contact sheet of every pose (--sheet).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "body/mesh_normals.hpp"
#include "body/model_loader.hpp"
#include "body/pose_benchmark.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/pose_sheet.hpp"
#include "util/atomic_file.hpp"

namespace cli {

PoseSheetWriter& pose_sheet_writer() {
  static PoseSheetWriter writer = nullptr;
  return writer;
}

}  // namespace cli

namespace {

const char* const kUsage =
    "usage: sequential-gallery bench-pose --model female|male|neutral|FILE.npz [--model ...]\n"
    "                                     [--label NAME ...] [--components N] [--out REPORT.md]\n"
    "                                     [--sheet SHEET.png] [--sheet-model NAME ...]\n"
    "                                     [--cell-size PX] [--pose NAME ...]\n"
    "Poses each model's mean body and its +-3 SD bodies of components 1..N (default 3) in the\n"
    "pose library and reports, per pose, the volume change of the limb region around the\n"
    "joint, the sharpest fold and the new self-intersections (worst body, mean in brackets)\n"
    "against the targets (|volume| <= 8 %, fold <= 60 deg, no intersections outside the fist).\n"
    "Several --model arguments are put side by side (e.g. today's weights and new ones);\n"
    "--label gives each its column title, in the same order (default: the --model text).\n"
    "Prints the markdown report; --out also writes it; --sheet draws each model's mean body in\n"
    "every pose into one labelled PNG (square cells of --cell-size pixels, default 320), or\n"
    "only the models named by --sheet-model (labels). --pose runs only the poses named (the\n"
    "others show as \"-\"; the sheet still draws every pose).\n";

// An argument as a shell would need it to read it back: single-quoted unless it is plain.
std::string shell_quoted(const std::string& arg) {
  const bool plain = !arg.empty() && arg.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_./=+-:,") == std::string::npos;
  if (plain) return arg;
  std::string out = "'";
  for (const char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string figures_line(const body::PoseFigures& f) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "vol %+.1f%% fold %.0f x %d", f.volume_change_percent,
                f.sharpest_fold_degrees, f.intersections.pairs);
  return buf;
}

// The contact sheet's cells for one model: its mean body in every pose.
cli::PoseSheetBlock sheet_block(const body::Model& model, const std::string& label) {
  cli::PoseSheetBlock block;
  block.title = label + ": mean body";
  block.model = &model;
  const body::BodyMesh mean = body::evaluate(model, Eigen::VectorXf::Zero(model.component_count()));
  for (const body::PoseDefinition& pose : body::pose_library()) {
    cli::PoseSheetCell cell;
    cell.pose = pose.name;
    cell.label.push_back(pose.name);
    const body::PosedBody posed = body::pose_body(model, mean, pose);
    cell.available = posed.available;
    if (posed.available) {
      cell.label.push_back(figures_line(body::measure_posed_body(model, posed, pose)));
      cell.mesh.vertices = posed.posed_vertices;
      cell.mesh.joints = posed.posed_joints;
      body::place_on_ground(cell.mesh);
      body::compute_vertex_normals(cell.mesh.vertices, model.faces, cell.mesh.normals);
    } else {
      cell.label.push_back("not available");
    }
    block.cells.push_back(std::move(cell));
  }
  return block;
}

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {"help"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown(
      {"help", "model", "label", "components", "out", "sheet", "sheet-model", "cell-size", "pose"});
  const std::vector<std::string> names = args.get_all("model");
  if (names.empty()) {
    throw cli::ArgError("bench-pose: give at least one --model\n" + std::string(kUsage));
  }
  std::vector<std::string> labels = args.get_all("label");
  if (labels.empty()) labels = names;
  if (labels.size() != names.size()) {
    throw cli::ArgError("bench-pose: " + std::to_string(labels.size()) + " --label for " +
                        std::to_string(names.size()) + " --model; give one per model or none");
  }
  const std::vector<std::string> sheet_models = args.get_all("sheet-model");
  for (const auto& m : sheet_models) {
    if (std::find(labels.begin(), labels.end(), m) == labels.end()) {
      throw cli::ArgError("bench-pose: --sheet-model '" + m + "' is not one of the models' labels");
    }
  }
  const int components = args.get_int("components", 3);
  if (components < 0 || components > 64) {
    throw cli::ArgError("bench-pose: --components must be 0..64, got " +
                        std::to_string(components));
  }
  const int cell_px = args.get_int("cell-size", 320);
  if (cell_px < 64 || cell_px > 2048) {
    throw cli::ArgError("bench-pose: --cell-size must be 64..2048 pixels");
  }
  const std::vector<std::string> poses = args.get_all("pose");
  body::require_known_poses(poses);  // before any model is loaded: a typo fails at once
  const auto out = args.get("out");
  const auto sheet = args.get("sheet");
  if (sheet && !cli::pose_sheet_writer()) {
    throw cli::ArgError(
        "bench-pose: --sheet needs the renderer, and this build has none "
        "(configured with SG_BUILD_GUI=OFF)");
  }
  for (const auto& [option, path] : {std::pair{"--out", out}, std::pair{"--sheet", sheet}}) {
    if (!path) continue;
    std::error_code ec;
    if (path->empty()) throw cli::ArgError(std::string("bench-pose: ") + option + " is empty");
    if (path->back() == '/' || std::filesystem::is_directory(*path, ec)) {
      throw cli::ArgError(std::string("bench-pose: ") + option + " " + *path +
                          " is a folder; give a file name");
    }
  }

  // Every model is loaded (and checked) before any is measured, so a typo fails at once.
  std::vector<body::Model> models;
  for (const auto& name : names) {
    body::Model m = body::resolve_model(name, components == 0 ? 1 : components);
    if (m.component_count() < components) {
      throw cli::ArgError("bench-pose: --components " + std::to_string(components) +
                          ": the model '" + name + "' has only " +
                          std::to_string(m.component_count()) + " shape components");
    }
    body::load_pose_correctives(m);
    models.push_back(std::move(m));
  }
  const body::PoseTargets targets;
  std::vector<body::ModelBenchmark> results;
  for (std::size_t i = 0; i < models.size(); ++i) {
    results.push_back(body::run_pose_benchmark(models[i], labels[i], components, targets, poses));
    const auto& r = results.back();
    const auto ran = std::count_if(r.poses.begin(), r.poses.end(),
                                   [](const body::PoseResult& p) { return p.asked; });
    std::fprintf(stderr, "bench-pose: %s: %zu bodies x %ld poses in %.1f s\n", labels[i].c_str(),
                 r.bodies.size(), static_cast<long>(ran), r.seconds);
  }

  std::string command = "sequential-gallery bench-pose";
  for (int i = 1; i < argc; ++i) command += " " + shell_quoted(argv[i]);
  std::string sheet_link;
  if (sheet) {
    namespace fs = std::filesystem;
    const fs::path base = out ? fs::absolute(*out).parent_path() : fs::current_path();
    sheet_link = fs::absolute(*sheet)
                     .lexically_normal()
                     .lexically_relative(base.lexically_normal())
                     .generic_string();
  }
  const std::string report = body::pose_benchmark_markdown(results, targets, command, sheet_link);
  std::cout << report;
  if (out) {
    util::write_file_atomically(*out, report);
    std::cout << "\nwrote " << *out << "\n";
  }
  if (sheet) {
    std::vector<cli::PoseSheetBlock> blocks;
    for (std::size_t i = 0; i < models.size(); ++i) {
      if (sheet_models.empty() ||
          std::find(sheet_models.begin(), sheet_models.end(), labels[i]) != sheet_models.end()) {
        blocks.push_back(sheet_block(models[i], labels[i]));
      }
    }
    cli::pose_sheet_writer()(*sheet, blocks, cell_px);
    std::cout << "wrote " << *sheet << "\n";
  }
  return 0;
}

const cli::CommandRegistration reg{
    "bench-pose", "pose benchmark of skinned body models: volume, folds, self-intersections", &run};

}  // namespace
