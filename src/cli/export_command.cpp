// `export`: write one body as glTF (.glb or .gltf) from the command line.
#include <iostream>
#include <string>
#include <vector>

#include "body/gltf_export.hpp"
#include "cli/arg_parser.hpp"
#include "cli/body_cli_common.hpp"
#include "cli/command_registry.hpp"

namespace {

int run(int argc_in, char** argv_in) {
  std::vector<std::string> store;
  auto argv_vec = cli::normalize_output_flag(argc_in, argv_in, store);
  const int argc = argc_in;
  char** argv = argv_vec.data();
  const cli::ArgParser args(argc, argv, {"no-morph", "morph-betas"}, {"betas", "x"});
  if (args.has("help")) {
    std::cout
        << "usage: sequential-gallery export [--model FILE.npz] [--components N]\n"
           "                                 [--betas B1 B2 ... | --x X1 X2 ...]\n"
           "                                 [--no-morph | --morph-betas] -o OUT.glb|OUT.gltf\n\n"
           "Writes the body as glTF 2.0 (metres, y up, feet on the ground, skeleton with\n"
           "skin weights, shape components as morph targets unless --no-morph).\n"
           "Morph targets: by default two per component (+3 and -3 sigma) with weights in\n"
           "[0,1], since Blender clamps negative shape-key values; --morph-betas writes one\n"
           "per component with weight = beta.\n"
           "--x takes normalized coordinates in [0,1] (beta = 6x - 3). Without --model the\n"
           "embedded default model is used.\n";
    return 0;
  }
  args.reject_unknown({"model", "components", "betas", "x", "no-morph", "morph-betas", "output"});
  const std::string out = args.require("output");
  cli::require_output_file(out);
  const body::Model model = cli::load_body_model(args);
  const Eigen::VectorXf betas = cli::read_betas(args, model);
  body::ExportOptions options;
  options.morph_targets = !args.has("no-morph");
  if (args.has("morph-betas")) options.morph_encoding = body::MorphEncoding::betas;
  body::export_gltf(model, betas, out, options);
  std::cout << "wrote " << out << ": model '" << model.name << "', " << model.vertex_count()
            << " vertices, " << model.faces.rows() << " faces, " << model.joint_count()
            << " joints, "
            << (!options.morph_targets ? 0
                : options.morph_encoding == body::MorphEncoding::betas
                    ? model.component_count()
                    : 2 * model.component_count())
            << " morph targets; betas [" << cli::format_betas(betas) << "]\n";
  return 0;
}

const cli::CommandRegistration reg{"export", "write a body as glTF (.glb/.gltf) for Blender etc.",
                                   &run};

}  // namespace
