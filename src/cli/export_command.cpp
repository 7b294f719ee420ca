// `export`: write one body as glTF (.glb or .gltf) or VRM 1.0 (.vrm) from the command line.
#include <iostream>
#include <string>
#include <vector>

#include "body/export_presets.hpp"
#include "body/gltf_export.hpp"
#include "body/model_loader.hpp"
#include "cli/arg_parser.hpp"
#include "cli/body_cli_common.hpp"
#include "cli/command_registry.hpp"

namespace {

std::string choice(const cli::ArgParser& args, const std::string& name,
                   const std::vector<std::string>& allowed, const std::string& fallback) {
  const std::string v = args.get_or(name, fallback);
  for (const auto& a : allowed) {
    if (v == a) return v;
  }
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : "|") + a;
  throw cli::ArgError("--" + name + " must be one of " + list + ", got '" + v + "'");
}

std::vector<std::string> split_authors(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  auto flush = [&] {
    const auto b = cur.find_first_not_of(' ');
    const auto e = cur.find_last_not_of(' ');
    if (b != std::string::npos) out.push_back(cur.substr(b, e - b + 1));
    cur.clear();
  };
  for (char c : s) {
    if (c == ';') {
      flush();
    } else {
      cur += c;
    }
  }
  flush();
  return out;
}

void print_help() {
  std::cout
      << "usage: sequential-gallery export [--model FILE.npz] [--components N] [--expressions N]\n"
         "                                 [--betas B1 B2 ... | --x X1 X2 ...]\n"
         "                                 [--target NAME=VALUE ...]\n"
         "                                 [--preset NAME] [--rest-pose a|t]\n"
         "                                 [--no-morph | --morph-betas] [--joint-names "
         "model|humanoid|unreal]\n"
         "                                 [--vrm-... meta options] -o OUT.glb|OUT.gltf|OUT.vrm\n\n"
         "--target (repeatable): e.g. height=1.80 mass=85 (or 180cm, 187lb): the body nearest\n"
         "to the given shape that meets them (names: see `measure --help`).\n\n"
         "Writes the body as glTF 2.0 (.glb binary, .gltf JSON) or as a VRM 1.0 avatar (.vrm):\n"
         "metres, y up, facing +Z, feet on the ground, a skeleton whose bones point along the\n"
         "limbs (each joint's +Y at its child), skin weights, UVs when the model has vt/ft.\n\n"
         "The base mesh is the designed body: with all morph weights at 0 (the default) the\n"
         "mesh is the design and matches the skeleton. Morph targets edit the design:\n"
         "  default        shape_NN_pos / shape_NN_neg; weight w adds +3w / -3w to beta NN\n"
         "                 (w in [0, 1]; Blender clamps negative shape-key values)\n"
         "  --morph-betas  shape_NN; weight w adds w to beta NN (w may be negative)\n"
         "  --no-morph     no morph targets\n"
         "  --expressions N  (SMPL-X) also the first N facial expressions as expr_NN targets;\n"
         "                 --components counts shape components only\n\n"
         "--rest-pose a   the model's own rest pose (A-pose for the default model; default)\n"
         "--rest-pose t   T-pose: arms horizontal, posed by the model's own skinning with its\n"
         "                pose correctives when the file has posedirs (always for .vrm)\n"
         "--joint-names humanoid  bones named as VRM humanoid bones (hips, leftUpperArm, ...)\n"
         "--joint-names unreal    bones named as the UE5 mannequin's (pelvis, thigh_l, ...)\n\n"
         "Presets (other options given with --preset override its choices):\n";
  for (const auto& p : body::export_presets()) {
    std::cout << "  " << p.name << std::string(9 - std::min<std::size_t>(8, p.name.size()), ' ')
              << p.extension << "  " << p.description << "\n";
  }
  std::cout
      << "\nVRM meta (.vrm): --vrm-name S, --vrm-version S, --vrm-authors 'A; B', "
         "--vrm-license-url U,\n"
         "  --vrm-avatar-permission onlyAuthor|onlySeparatelyLicensedPerson|everyone,\n"
         "  --vrm-commercial-usage personalNonProfit|personalProfit|corporation,\n"
         "  --vrm-credit-notation required|unnecessary,\n"
         "  --vrm-modification prohibited|allowModification|allowModificationRedistribution,\n"
         "  --vrm-allow-redistribution. Defaults: the model's name, author 'unknown', the VRM\n"
         "  public licence URL, only the author, personal non-profit, credit required, no\n"
         "  modification or redistribution.\n\n"
         "--x takes normalized coordinates in [0,1] (beta = 6x - 3). Without --model the\n"
         "embedded default model is used. Asking for more components or betas than the file\n"
         "has is an error.\n";
}

int run(int argc_in, char** argv_in) {
  std::vector<std::string> store;
  auto argv_vec = cli::normalize_output_flag(argc_in, argv_in, store);
  const int argc = argc_in;
  char** argv = argv_vec.data();
  const cli::ArgParser args(argc, argv, {"no-morph", "morph-betas", "vrm-allow-redistribution"},
                            {"betas", "x"});
  if (args.has("help")) {
    print_help();
    return 0;
  }
  args.reject_unknown({"model",
                       "components",
                       "expressions",
                       "betas",
                       "x",
                       "target",
                       "no-morph",
                       "morph-betas",
                       "output",
                       "preset",
                       "rest-pose",
                       "joint-names",
                       "vrm-name",
                       "vrm-version",
                       "vrm-authors",
                       "vrm-license-url",
                       "vrm-avatar-permission",
                       "vrm-commercial-usage",
                       "vrm-credit-notation",
                       "vrm-modification",
                       "vrm-allow-redistribution"});
  if (args.has("no-morph") && args.has("morph-betas")) {
    throw cli::ArgError("--no-morph and --morph-betas contradict each other: choose one");
  }
  body::ExportOptions options;
  std::string preset_ext;
  if (const auto name = args.get("preset")) {
    const auto preset = body::find_export_preset(*name);
    if (!preset) {
      std::string list;
      for (const auto& p : body::export_presets()) list += (list.empty() ? "" : "|") + p.name;
      throw cli::ArgError("--preset must be one of " + list + ", got '" + *name + "'");
    }
    options = preset->options;
    preset_ext = preset->extension;
  }
  const std::string out = args.require("output");
  cli::require_output_file(out);
  const std::string ext = std::filesystem::path(out).extension().string();
  if (preset_ext == ".vrm" && ext != ".vrm") {
    throw cli::ArgError("--preset vrm writes a VRM avatar: name the output file *.vrm");
  }
  if (args.has("rest-pose")) {
    const std::string r = choice(args, "rest-pose", {"a", "t"}, "a");
    options.rest_pose = r == "t" ? body::RestPose::t : body::RestPose::model;
    if (r == "a" && ext == ".vrm") {
      throw cli::ArgError("--rest-pose a: VRM 1.0 requires a T-pose (use --rest-pose t)");
    }
  }
  if (args.has("joint-names")) {
    const std::string naming =
        choice(args, "joint-names", {"model", "humanoid", "unreal"}, "model");
    options.joint_naming = naming == "humanoid" ? body::JointNaming::humanoid
                           : naming == "unreal" ? body::JointNaming::unreal
                                                : body::JointNaming::model;
  }
  if (args.has("no-morph")) options.morph_targets = false;
  if (args.has("morph-betas")) options.morph_encoding = body::MorphEncoding::betas;
  body::VrmMeta& meta = options.vrm;
  meta.name = args.get_text("vrm-name", meta.name);
  meta.version = args.get_text("vrm-version", meta.version);
  if (args.has("vrm-authors")) meta.authors = split_authors(args.get_text("vrm-authors", ""));
  meta.license_url = args.get_text("vrm-license-url", meta.license_url);
  meta.avatar_permission =
      choice(args, "vrm-avatar-permission",
             {"onlyAuthor", "onlySeparatelyLicensedPerson", "everyone"}, meta.avatar_permission);
  meta.commercial_usage =
      choice(args, "vrm-commercial-usage", {"personalNonProfit", "personalProfit", "corporation"},
             meta.commercial_usage);
  meta.credit_notation =
      choice(args, "vrm-credit-notation", {"required", "unnecessary"}, meta.credit_notation);
  meta.modification = choice(args, "vrm-modification",
                             {"prohibited", "allowModification", "allowModificationRedistribution"},
                             meta.modification);
  if (args.has("vrm-allow-redistribution")) meta.allow_redistribution = true;

  body::Model model = cli::load_body_model(args);
  if (options.rest_pose == body::RestPose::t || ext == ".vrm") body::load_pose_correctives(model);
  const Eigen::VectorXf betas = cli::apply_targets(args, model, cli::read_betas(args, model));
  const int targets = body::morph_target_count(model, options);
  if (targets > body::kManyMorphTargets) {
    std::cerr << "warning: writing " << targets << " morph targets (" << model.component_count()
              << " shape components"
              << (model.expression_dirs.cols() > 0
                      ? ", " + std::to_string(model.expression_dirs.cols()) + " expressions"
                      : std::string())
              << "): a large file that some tools load slowly; --components N, --morph-betas "
                 "or --no-morph make fewer\n";
  }
  body::export_gltf(model, betas, out, options);
  std::cout << "wrote " << out << ": model '" << model.name << "', " << model.vertex_count()
            << " vertices, " << model.faces.rows() << " faces, " << model.joint_count()
            << " joints, " << targets << " morph targets" << (model.uvs.rows() > 0 ? ", UVs" : "")
            << "; betas [" << cli::format_betas(betas) << "]\n";
  return 0;
}

const cli::CommandRegistration reg{
    "export", "write a body as glTF (.glb/.gltf) or VRM 1.0 (.vrm) for Blender, Unity etc.", &run};

}  // namespace
