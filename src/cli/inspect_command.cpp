// `inspect`: what a model file holds and whether it is usable.
#include <cstdio>
#include <iostream>

#include "body/model_loader.hpp"
#include "body/npz_reader.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"

namespace {

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {});
  if (args.has("help")) {
    std::cout << "usage: sequential-gallery inspect --model female|male|neutral|FILE.npz\n\n"
                 "Lists the arrays in the file (dtype, shape, storage) and says whether it is a\n"
                 "usable SMPL-family model; exit code 0 if usable, 1 if not.\n";
    return 0;
  }
  args.reject_unknown({"model"});
  const std::string path = args.require("model");
  std::printf("file    %s\n", path.c_str());
  try {
    // A built-in name means the embedded model, as everywhere else --model is taken.
    const body::NpzArchive npz = body::is_builtin_model_name(path)
                                     ? body::open_builtin_model_archive(path)
                                     : body::NpzArchive::open_file(path);
    const auto entries = npz.list();
    std::printf("arrays  %zu\n", entries.size());
    for (const auto& e : entries) {
      if (e.header) {
        const auto& h = *e.header;
        std::printf("  %-22s %-8s %-18s %s%s%s\n", e.name.c_str(), h.dtype_name().c_str(),
                    h.shape_string().c_str(), h.fortran_order ? "F-order " : "",
                    h.big_endian ? "big-endian " : "", e.compressed ? "deflate" : "stored");
        if (h.needs_pickle()) std::printf("  %-22s (needs Python pickle: skipped)\n", "");
      } else {
        std::printf("  %-22s unreadable: %s\n", e.name.c_str(), e.problem.c_str());
      }
    }
  } catch (const body::ModelError& e) {
    std::printf("usable  no: %s\n", e.what());
    return 1;
  }
  try {
    // Every value is checked, but only one shape component is kept: the counts come from the
    // headers, and converting 400 columns of an SMPL-X file would only be thrown away.
    const body::ModelCheck check = body::check_model(path);
    const body::Model& m = check.model;
    std::printf("usable  yes: %d vertices, %d faces, %d joints (root '%s'), %d shape components\n",
                m.vertex_count(), static_cast<int>(m.faces.rows()), m.joint_count(),
                m.joint_names.empty() ? "" : m.joint_names.front().c_str(), m.total_components);
    if (m.total_expressions > 0) {
      std::printf("extras  %d expression components (SMPL-X; exported with --expressions N)\n",
                  m.total_expressions);
    }
    if (check.pose_columns > 0) {
      const bool smpl_layout = check.pose_columns == 9 * (m.joint_count() - 1);
      std::printf("extras  posedirs with %d columns: %s\n", check.pose_columns,
                  smpl_layout ? "pose correctives for --rest-pose t"
                              : "not in SMPL's 9 (J - 1) layout, not applied");
    }
    if (m.uvs.rows() > 0) {
      std::printf("extras  %d texture coordinates (vt/ft): exported as TEXCOORD_0\n",
                  static_cast<int>(m.uvs.rows()));
    }
    const auto mesh = body::evaluate(m, Eigen::VectorXf());
    std::printf("height  %.4f m (mean shape)\n",
                mesh.vertices.col(1).maxCoeff() - mesh.vertices.col(1).minCoeff());
    return 0;
  } catch (const body::ModelError& e) {
    std::printf("usable  no: %s\n", e.what());
    return 1;
  }
}

const cli::CommandRegistration reg{"inspect", "list what a model .npz holds and if it is usable",
                                   &run};

}  // namespace
