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
                 "                                  [--betas B1 B2 ... | --x X1 X2 ...]\n"
                 "                                  [--target NAME=VALUE ...]\n\n"
                 "Prints height, chest, waist and hip circumferences (metres; convex hull of\n"
                 "horizontal slices, as a tape measure does), volume, mass, BMI, shoulder\n"
                 "width, inseam, arm length, and the neck, deltoid breadth, upper-arm, thigh and\n"
                 "calf measures across the limbs (landmarks: src/body/measurements.hpp).\n\n"
                 "--target NAME=VALUE (repeatable) measures the body nearest to the given shape\n"
                 "that meets the targets instead: names " +
                     body::measurement_names() +
                     ";\nvalues in m, kg, kg/m^2 or with a unit (180cm, 71in, 187lb).\n";
    return 0;
  }
  args.reject_unknown({"model", "components", "betas", "x", "target"});
  const body::Model model = cli::load_body_model(args);
  const Eigen::VectorXf betas = cli::apply_targets(args, model, cli::read_betas(args, model));
  const body::Measurements m = body::measure(model, betas);
  std::printf("model   %s (%d components)\n", model.name.c_str(), model.component_count());
  std::printf("betas   [%s]\n", cli::format_betas(betas).c_str());
  std::printf("height  %.4f m  (%.1f cm)\n", m.height, 100.0 * m.height);
  line("chest", m.chest, m.chest_height);
  line("waist", m.waist, m.waist_height);
  line("hips", m.hips, m.hips_height);
  std::printf("volume  %.4f m^3  (%.1f l)\n", m.volume, 1000.0 * m.volume);
  std::printf("mass    %.1f kg  (volume x %.0f kg/m^3)\n", m.mass, body::kBodyDensity);
  std::printf("bmi     %.1f kg/m^2\n", m.bmi);
  const auto length = [](const char* label, double value, const char* why) {
    if (std::isnan(value)) {
      std::printf("%-15s n/a (%s)\n", label, why);
    } else {
      std::printf("%-15s %.4f m  (%.1f cm)\n", label, value, 100.0 * value);
    }
  };
  length("shoulder_width", m.shoulder_width, "no left/right_shoulder joints");
  length("inseam", m.inseam, "no crotch between two legs");
  length("arm_length", m.arm_length, "no shoulder/elbow/wrist joints");
  length("neck", m.neck, "no neck/head joints");
  length("bideltoid", m.bideltoid, "no shoulder/elbow joints");
  length("upper_arm", m.upper_arm, "no shoulder/elbow joints");
  length("thigh", m.thigh, "no hip/knee joints");
  length("calf", m.calf, "no knee/ankle joints");
  return 0;
}

const cli::CommandRegistration reg{
    "measure", "print height, chest/waist/hip girths, volume and mass of a body", &run};

}  // namespace
