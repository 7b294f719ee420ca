// `generate-default-model`: builds the embedded default body model (template mannequin,
// population, PCA) and writes it as an SMPL-layout .npz (assets/default_body.npz).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "default_model/default_model.hpp"
#include "default_model/preview_rasterizer.hpp"
#include "util/atomic_file.hpp"

namespace {

std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// Front and side views of the mean and of components 1..5 at -3 and +3.
void write_preview(const default_model::GeneratedModel& m, const std::string& path) {
  using default_model::View;
  const int V = static_cast<int>(m.v_template.rows());
  const std::vector<std::uint32_t> tris(m.faces.data(), m.faces.data() + m.faces.size());
  const int cols = 11, cw = 300, ch = 420;
  default_model::Image image(cols * cw, 2 * ch);
  int c = 0;
  auto put = [&](int k, float b) {
    std::vector<Eigen::Vector3f> v(V);
    for (int i = 0; i < V; ++i)
      for (int a = 0; a < 3; ++a)
        v[i][a] = m.v_template(i, a) + (k >= 0 ? b * m.shapedirs(3 * i + a, k) : 0.0f);
    default_model::draw_mesh(image, c * cw, 0, cw, ch, v, tris, View::kFront, {0, 0.95f, 0}, 200);
    default_model::draw_mesh(image, c * cw, ch, cw, ch, v, tris, View::kSide, {0, 0.95f, 0}, 200);
    ++c;
  };
  put(-1, 0);
  for (int k = 0; k < 5 && k < m.shapedirs.cols(); ++k) {
    put(k, -3);
    put(k, 3);
  }
  default_model::write_png(image, path);
}

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {"check"});
  if (args.has("help")) {
    std::cout
        << "usage: sequential-gallery generate-default-model [--output FILE.npz] [--check]\n"
           "          [--population N] [--components K] [--seed S] [--preview FILE.png]\n\n"
           "Builds the embedded default body model: a template mannequin (implicit surface,\n"
           "marching tetrahedra, remeshing), SMPL's 24-joint rig, a population of bodies from\n"
           "anthropometric survey statistics, and its PCA shape space (betas ~ N(0, 1)).\n"
           "Writes an SMPL-layout .npz (default assets/default_body.npz). --check compares\n"
           "with the existing file instead of writing (exit 1 if it differs). --preview\n"
           "writes a software-rendered PNG of the mean and components 1-5 at -3/+3.\n";
    return 0;
  }
  args.reject_unknown({"output", "check", "population", "components", "seed", "preview"});
  default_model::GeneratorOptions options;
  options.population = args.get_int("population", options.population);
  options.components = args.get_int("components", options.components);
  options.seed =
      static_cast<std::uint64_t>(std::stoull(args.get_or("seed", std::to_string(options.seed))));
  if (options.population < 20 || options.components < 1)
    throw cli::ArgError("--population must be >= 20 and --components >= 1");
  const std::string output = args.get_or("output", "assets/default_body.npz");

  const auto t0 = std::chrono::steady_clock::now();
  const default_model::GeneratedModel model = default_model::generate_default_model(options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("vertices %ld, faces %ld, components %ld, population %d, %.1f s\n",
              static_cast<long>(model.v_template.rows()), static_cast<long>(model.faces.rows()),
              static_cast<long>(model.shapedirs.cols()), options.population, seconds);
  std::printf("variance share:");
  for (int k = 0; k < model.variance_share.size(); ++k)
    std::printf(" %.4f", model.variance_share[k]);
  std::printf("\n");
  if (args.has("preview")) write_preview(model, args.require("preview"));

  if (args.has("check")) {
    if (read_file(output) != model.npz) {
      std::fprintf(stderr, "generate-default-model: %s differs from the generator's output\n",
                   output.c_str());
      return 1;
    }
    std::printf("%s is up to date (%zu bytes)\n", output.c_str(), model.npz.size());
    return 0;
  }
  util::write_file_atomically(output, model.npz.data(), model.npz.size());
  std::printf("wrote %s (%zu bytes)\n", output.c_str(), model.npz.size());
  return 0;
}

const cli::CommandRegistration reg{
    "generate-default-model", "build the embedded default body model (assets/default_body.npz)",
    &run};

}  // namespace
