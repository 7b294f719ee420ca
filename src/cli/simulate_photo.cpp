#include "cli/simulate_photo.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "app/session.hpp"
#include "bench/simulated_person.hpp"
#include "cli/simulate_common.hpp"
#include "spaces/photo_enhancement.hpp"
#include "spaces/photo_image.hpp"
#include "spaces/photo_perception.hpp"

namespace cli {

namespace {

// Parameter indices (spaces/photo_enhancement.hpp): brightness, contrast, saturation, then
// cyan-red / magenta-green / yellow-blue for shadows (3-5), midtones (6-8), highlights (9-11).
enum Parameter {
  kBrightness = 0,
  kContrast = 1,
  kSaturation = 2,
  kShadowRed = 3,
  kShadowBlue = 5,
  kMidRed = 6,
  kMidBlue = 8,
  kHighRed = 9,
  kHighBlue = 11,
};

Eigen::VectorXd point_of(const std::array<double, spaces::kPhotoParameters>& p) {
  Eigen::VectorXd x(spaces::kPhotoParameters);
  for (int i = 0; i < spaces::kPhotoParameters; ++i) {
    x[i] = 0.5 * (p[static_cast<std::size_t>(i)] + 1.0);
  }
  return x;
}

// The named tasks, as a person would describe them, in the window's -1..+1 units.
Eigen::VectorXd named_target(const std::string& name) {
  std::array<double, spaces::kPhotoParameters> p{};
  if (name == "warmer-brighter") {
    p[kBrightness] = 0.4;
    p[kSaturation] = 0.1;
    p[kShadowRed] = 0.2;
    p[kMidRed] = 0.35;
    p[kHighRed] = 0.25;
    p[kShadowBlue] = -0.3;  // towards yellow
    p[kMidBlue] = -0.45;
    p[kHighBlue] = -0.35;
  } else if (name == "cooler") {
    p[kShadowRed] = -0.2;
    p[kMidRed] = -0.3;
    p[kHighRed] = -0.2;
    p[kShadowBlue] = 0.3;
    p[kMidBlue] = 0.4;
    p[kHighBlue] = 0.3;
  } else if (name == "more-contrast") {
    p[kContrast] = 0.6;
    p[kSaturation] = 0.3;
  } else {
    throw ArgError("--target: '" + name +
                   "' is not random, warmer-brighter, cooler or more-contrast");
  }
  return point_of(p);
}

// A random edit people might make: each parameter N(0, 0.4) on its -1..+1 range, truncated to
// +-0.9 (the population photo_population() gives the optimizer), from the trial's own stream.
Eigen::VectorXd random_target(std::uint64_t seed) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + 0x70686F746FULL);
  std::normal_distribution<double> normal(0.0, 0.4);
  std::array<double, spaces::kPhotoParameters> p{};
  for (double& v : p) {
    do {
      v = normal(rng);
    } while (std::abs(v) > 0.9);
  }
  return point_of(p);
}

}  // namespace

int run_photo_simulation(const ArgParser& args) {
  std::set<std::string> known{"function",
                              "user",
                              "jnd-delta-e",
                              "target",
                              "image",
                              "trials",
                              "iterations",
                              "seed",
                              "grid",
                              "levels",
                              "csv",
                              "per-trial-csv",
                              "quiet",
                              "no-adapt",
                              "no-perceptual-scale",
                              "no-target-model",
                              "min-plane-delta-e",
                              "distinct-delta-e",
                              "compare-delta-e",
                              "choice-temperature"};
  known.insert(search_option_names().begin(), search_option_names().end());
  args.reject_unknown(known);
  const std::string user = args.get_or("user", "zoom-jnd");
  if (user != "zoom-jnd") {
    throw ArgError("--function photo: the user is zoom-jnd (--user zoom-jnd)");
  }
  const double jnd = args.get_double("jnd-delta-e", spaces::kPhotoJndDeltaE);
  if (!(jnd >= 0.0 && jnd <= 50.0)) throw ArgError("--jnd-delta-e must be in [0, 50]");
  const int trials = args.get_int("trials", 10);
  const int iterations = args.get_int("iterations", 15);
  const int seed = args.get_int("seed", 1000);
  const int grid = args.get_int("grid", 3);
  const int levels = args.get_int("levels", 4);
  if (trials < 1 || iterations < 1) throw ArgError("--trials and --iterations must be >= 1");
  if (grid != 3 && grid != 5) throw ArgError("--grid must be 3 or 5 (the window's grids)");
  if (levels < 1 || levels > 8) throw ArgError("--levels must be between 1 and 8");
  const std::string target_mode = args.get_or("target", "random");
  const Eigen::VectorXd fixed_target =
      target_mode == "random" ? Eigen::VectorXd() : named_target(target_mode);
  const bool quiet = args.has("quiet");
  const bool adapt = !args.has("no-adapt");
  const bool perceptual_scale = !args.has("no-perceptual-scale");
  const bool target_model = !args.has("no-target-model");

  // The session keeps the window's distance between cells (the person's JND is finer).
  const double distinct = args.get_double("distinct-delta-e", spaces::kPhotoDistinctDeltaE);
  if (!(distinct >= 0.1 && distinct <= 50.0)) {
    throw ArgError("--distinct-delta-e must be in [0.1, 50]");
  }
  app::ZoomPolicy policy = spaces::photo_zoom_policy(distinct);
  policy.compare_mm = args.get_double("compare-delta-e", policy.compare_mm);
  if (!(policy.compare_mm >= 0.0 && policy.compare_mm <= 100.0)) {
    throw ArgError("--compare-delta-e must be in [0, 100]");
  }
  sps::SearchOptions options = read_search_options(args);
  // The window's planes for photos (spaces::PhotoSpace::plane_axes), unless told otherwise.
  if (!args.has("plane-axes")) options.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  use_space_uncertainty_size(args, spaces::photo_uncertainty_size(), options);
  options.min_plane_length = args.get_double("min-plane-delta-e", spaces::kPhotoMinPlaneDeltaE);
  if (!(options.min_plane_length >= 0.0 && options.min_plane_length <= 100.0)) {
    throw ArgError("--min-plane-delta-e must be in [0, 100]");
  }
  options.choice_temperature_mm =
      args.get_double("choice-temperature", options.choice_temperature_mm);
  if (!(options.choice_temperature_mm >= 0.01 && options.choice_temperature_mm <= 100.0)) {
    throw ArgError("--choice-temperature must be in [0.01, 100]");
  }

  const std::string image_path = args.get_or("image", "");
  const spaces::Image image =
      image_path.empty() ? spaces::default_photo() : spaces::load_image(image_path);
  const spaces::PhotoDistance distance(image);
  const app::PairwiseDistance pairwise = [&distance](const std::vector<Eigen::VectorXd>& xs) {
    return distance.pairwise(xs);
  };
  const Eigen::VectorXd scale = distance.direction_scale();

  SimulationResults results(iterations, seed, true);
  for (int trial = 0; trial < trials; ++trial) {
    const auto trial_seed = static_cast<std::uint64_t>(seed + trial);
    const Eigen::VectorXd target =
        fixed_target.size() > 0 ? fixed_target : random_target(trial_seed);
    const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
      return distance.to_target(xs, target);
    };
    app::SessionSettings settings;
    settings.space = "photo";
    settings.components = spaces::kPhotoParameters;
    settings.grid_size = grid;
    settings.zoom_levels = levels;
    settings.seed = trial_seed;
    app::Session session(settings, options);
    if (perceptual_scale) {
      session.set_perceptual_scale(scale);
      if (target_model) session.set_population(spaces::photo_population());
    }
    if (adapt) session.set_perceptual_distance(pairwise, policy);
    play_trial(session, to_target, pairwise, jnd, policy.look_alike_mm, trial_seed, results);
    if (!quiet) std::cerr << "\rtrial " << (trial + 1) << "/" << trials << std::flush;
  }
  if (!quiet) std::cerr << "\n";

  std::ostringstream title;
  title << "# " << sps::method_name(options.method) << " on photo ("
        << (image_path.empty() ? std::string("built-in landscape") : image_path)
        << ", 12 parameters), user zoom-jnd (" << grid << "x" << grid << ", " << levels
        << " levels, JND " << jnd << " Delta E00; cells kept " << policy.look_alike_mm << " apart"
        << (adapt ? "" : ", no zoom adaptation")
        << (perceptual_scale ? "" : ", no perceptual scale")
        << (perceptual_scale && !target_model ? ", no target model" : "") << "), target "
        << target_mode << ", " << trials << " trials, seeds " << seed << "-" << (seed + trials - 1)
        << "; gap = mean CIEDE2000 of the best edit so far to the target";
  write_simulation_results(args, title.str(), results);
  return 0;
}

}  // namespace cli
