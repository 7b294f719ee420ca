// `uv-sheet`: a model's texture layout (vt/ft) and a checkerboard on its mean body, front and
// back, in one PNG, drawn by the software rasteriser (no GL): for judging seams, stretch and
// the islands' packing.
#include <iostream>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "cli/arg_parser.hpp"
#include "cli/body_cli_common.hpp"
#include "cli/command_registry.hpp"
#include "default_model/preview_rasterizer.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery uv-sheet [--model female|male|neutral|FILE.npz] -o OUT.png\n"
    "                                   [--size PIXELS] [--checks N]\n"
    "Draws the model's texture layout (each island in a colour of its own, flipped triangles in\n"
    "red) beside its mean body front and back with an N x N checkerboard (default 32) on the\n"
    "texture. The model must have texture coordinates (vt and ft).\n";

int run(int argc, char** argv_in) {
  std::vector<std::string> store;
  auto argv = cli::normalize_output_flag(argc, argv_in, store);
  cli::ArgParser args(argc, argv.data(), {"help"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help", "model", "o", "output", "size", "checks", "components"});
  const auto out = args.get("o") ? *args.get("o") : args.get("output");
  if (!out) throw cli::ArgError("uv-sheet: -o OUT.png is required\n" + std::string(kUsage));
  cli::require_output_file(*out);
  const int size = args.get_int("size", 700);
  if (size < 64 || size > 4096) throw cli::ArgError("uv-sheet: --size must be 64..4096");
  const int checks = args.get_int("checks", 32);
  if (checks < 1 || checks > 512) throw cli::ArgError("uv-sheet: --checks must be 1..512");
  const body::Model model = cli::load_body_model(args);
  if (model.uvs.rows() == 0 || model.uv_faces.rows() != model.faces.rows())
    throw cli::ArgError("uv-sheet: model '" + model.name + "' has no texture coordinates (vt/ft)");

  const body::BodyMesh mesh = body::evaluate(model, Eigen::VectorXf::Zero(0));
  std::vector<Eigen::Vector3f> vertices(static_cast<std::size_t>(mesh.vertices.rows()));
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    vertices[static_cast<std::size_t>(v)] = mesh.vertices.row(v).transpose();
  std::vector<std::uint32_t> triangles;
  std::vector<Eigen::Vector2f> corner_uv;
  // Islands: triangles joined through shared texture vertices.
  std::vector<int> parent(static_cast<std::size_t>(model.uvs.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (Eigen::Index f = 0; f < model.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      triangles.push_back(model.faces(f, c));
      corner_uv.push_back(model.uvs.row(model.uv_faces(f, c)).transpose());
      parent[find(static_cast<int>(model.uv_faces(f, c)))] =
          find(static_cast<int>(model.uv_faces(f, (c + 1) % 3)));
    }
  std::vector<int> island;
  for (Eigen::Index f = 0; f < model.faces.rows(); ++f)
    island.push_back(find(static_cast<int>(model.uv_faces(f, 0))));

  default_model::Image image(3 * size, size, 255);
  default_model::draw_uv_layout(image, 0, 0, size, corner_uv, island);
  const float top = mesh.vertices.col(1).maxCoeff(), bottom = mesh.vertices.col(1).minCoeff();
  const Eigen::Vector3f centre(0, 0.5f * (top + bottom), 0);
  const float scale = 0.92f * size / (top - bottom);
  default_model::draw_mesh(image, size, 0, size, size, vertices, triangles,
                           default_model::View::kFront, centre, scale, &corner_uv, checks);
  default_model::draw_mesh(image, 2 * size, 0, size, size, vertices, triangles,
                           default_model::View::kBack, centre, scale, &corner_uv, checks);
  default_model::write_png(image, *out);
  std::cout << "wrote " << *out << ": " << model.uvs.rows() << " texture vertices, "
            << std::set<int>(island.begin(), island.end()).size() << " islands\n";
  return 0;
}

const cli::CommandRegistration reg{
    "uv-sheet", "draw a model's texture layout and a checkerboard on its body", &run};

}  // namespace
