// `measure`: print height and tape-measure girths of a body.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "body/measurements.hpp"
#include "cli/arg_parser.hpp"
#include "cli/body_cli_common.hpp"
#include "cli/command_registry.hpp"

namespace {

void line(const char* label, double value, double at) {
  if (std::isnan(at)) {
    std::printf("%-7s n/a (no torso slice in the landmark band)\n", label);
  } else {
    std::printf("%-7s %.4f m  (%.1f cm, slice at %.3f m)\n", label, value, 100.0 * value, at);
  }
}

int run(int argc_in, char** argv_in) {
  std::vector<std::string> store;
  auto argv_vec = cli::normalize_output_flag(argc_in, argv_in, store);
  const int argc = argc_in;
  char** argv = argv_vec.data();
  const cli::ArgParser args(argc, argv, {}, {"betas", "x"});
  if (args.has("help")) {
    std::cout << "usage: sequential-gallery measure [--model female|male|neutral|FILE.npz] "
                 "[--components N]\n"
                 "                                  [--betas B1 B2 ... | --x X1 X2 ...]\n\n"
                 "Prints height and chest, waist and hip circumferences (metres), measured\n"
                 "as the convex hull of horizontal slices, as a tape measure does.\n";
    return 0;
  }
  args.reject_unknown({"model", "components", "betas", "x"});
  const body::Model model = cli::load_body_model(args);
  const Eigen::VectorXf betas = cli::read_betas(args, model);
  const body::Measurements m = body::measure(model, betas);
  std::printf("model   %s (%d components)\n", model.name.c_str(), model.component_count());
  std::printf("betas   [%s]\n", cli::format_betas(betas).c_str());
  std::printf("height  %.4f m  (%.1f cm)\n", m.height, 100.0 * m.height);
  line("chest", m.chest, m.chest_height);
  line("waist", m.waist, m.waist_height);
  line("hips", m.hips, m.hips_height);
  std::printf("volume  %.4f m^3  (%.1f l)\n", m.volume, 1000.0 * m.volume);
  std::printf("mass    %.1f kg  (volume x %.0f kg/m^3)\n", m.mass, body::kBodyDensity);
  return 0;
}

const cli::CommandRegistration reg{
    "measure", "print height, chest/waist/hip girths, volume and mass of a body", &run};

}  // namespace
