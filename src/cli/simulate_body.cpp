#include "cli/simulate_body.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "app/cell_visibility.hpp"
#include "app/session.hpp"
#include "bench/simulated_person.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "body/shape_distance.hpp"
#include "cli/simulate_common.hpp"
#include "spaces/body_framing.hpp"
#include "spaces/body_holds.hpp"
#include "spaces/body_space.hpp"

namespace cli {

namespace {

// --model FILE | neutral | female | male (built in), as the window and the other commands.
body::Model load_benchmark_model(const ArgParser& args, int components) {
  const std::string name = args.get_or("model", "neutral");
  return body::resolve_model(name == "default" ? "neutral" : name, components);
}

// Target betas i.i.d. N(0, 1) truncated to +-2.5 (rejection), from the trial's own stream.
Eigen::VectorXf random_target(int k, std::uint64_t seed) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + 0x7461726765ULL);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  Eigen::VectorXf betas(k);
  for (int i = 0; i < k; ++i) {
    float b = 0.0f;
    do {
      b = normal(rng);
    } while (std::abs(b) > 2.5f);
    betas[i] = b;
  }
  return betas;
}

// Holds with a stopwatch: where the time of a held search goes (the surface's solves and
// normals, for the optimizer's planes and the centres of the planes shown, and the projection
// of each cell).
struct HoldClock {
  std::mutex mutex;
  double surface_seconds = 0.0;
  double cell_seconds = 0.0;
  long surface_calls = 0;
  long cells = 0;
};

class TimedHolds : public app::ConstraintProjector {
 public:
  TimedHolds(std::shared_ptr<const app::ConstraintProjector> inner,
             std::shared_ptr<HoldClock> clock)
      : inner_(std::move(inner)), clock_(std::move(clock)) {}
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    return timed([&] { return inner_->project(x); }, false);
  }
  Eigen::MatrixXd normals(const Eigen::VectorXd& x) const override {
    return timed([&] { return inner_->normals(x); }, false);
  }
  // Called from two threads at once (Session::cells_at): the clock has a lock.
  Eigen::VectorXd project_near(const Eigen::VectorXd& x,
                               const Eigen::MatrixXd& nearby_normals) const override {
    return timed([&] { return inner_->project_near(x, nearby_normals); }, true);
  }
  std::string description() const override { return inner_->description(); }
  std::vector<app::HeldValue> held_values() const override { return inner_->held_values(); }

 private:
  template <typename F>
  auto timed(const F& f, bool cell) const -> decltype(f()) {
    const auto t0 = std::chrono::steady_clock::now();
    auto result = f();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::lock_guard<std::mutex> lock(clock_->mutex);
    (cell ? clock_->cell_seconds : clock_->surface_seconds) += seconds;
    ++(cell ? clock_->cells : clock_->surface_calls);
    return result;
  }

  std::shared_ptr<const app::ConstraintProjector> inner_;
  std::shared_ptr<HoldClock> clock_;
};

}  // namespace

int run_body_simulation(const ArgParser& args) {
  std::set<std::string> known{"function",
                              "model",
                              "components",
                              "target",
                              "target-betas",
                              "user",
                              "jnd-mm",
                              "jnd-px",
                              "cell-px",
                              "framing",
                              "trials",
                              "iterations",
                              "seed",
                              "grid",
                              "levels",
                              "csv",
                              "per-trial-csv",
                              "quiet",
                              "no-adapt",
                              "distinct-mm",
                              "no-perceptual-scale",
                              "diagonal-metric",
                              "min-plane-mm",
                              "uncertainty-min-side",
                              "no-perceptual-ls",
                              "perceptual-btl",
                              "no-mean-centre",
                              "compare-mm",
                              "zoom-factors",
                              "hold",
                              "no-target-model",
                              "choice-temperature-mm"};
  known.insert(search_option_names().begin(), search_option_names().end());
  args.reject_unknown(known);
  const std::string user = args.get_or("user", "zoom-jnd");
  if (user != "zoom-jnd") throw ArgError("--function body: the user is zoom-jnd (--user zoom-jnd)");
  // The pixel person: cannot tell apart cells whose distances to the target differ by less
  // than what D pixels show in a cell of N pixels, and the session and the look-alike count
  // use the same threshold, as the window does at that cell size.
  const bool pixel_person = args.has("jnd-px");
  const int cell_px = args.get_int("cell-px", app::kDefaultCellPx);
  const double jnd_px = args.get_double("jnd-px", app::kDefaultJndPx);
  if (cell_px < 16 || cell_px > 8192) throw ArgError("--cell-px must be in [16, 8192]");
  if (!(jnd_px >= 0.0 && jnd_px <= 100.0)) throw ArgError("--jnd-px must be in [0, 100]");
  if (pixel_person && args.has("jnd-mm")) {
    throw ArgError("--jnd-px and --jnd-mm: give one (the person's threshold in pixels or in mm)");
  }
  const double pixel_mm = app::look_alike_mm(cell_px, jnd_px);
  // The pixel person sees each grid framed as the window frames it (--framing: close-ups, the
  // window's default, or the whole body).
  const std::string framing_name = args.get_or("framing", "close-ups");
  if (framing_name != "close-ups" && framing_name != "whole-body") {
    throw ArgError("--framing: close-ups or whole-body, not '" + framing_name + "'");
  }
  const spaces::BodyFraming framing = framing_name == "whole-body" ? spaces::BodyFraming::kWholeBody
                                                                   : spaces::BodyFraming::kCloseUps;
  const double jnd_mm = pixel_person ? pixel_mm : args.get_double("jnd-mm", 5.0);
  const double clone_mm = pixel_person ? pixel_mm : app::kCloneMm;
  const int trials = args.get_int("trials", 10);
  const int iterations = args.get_int("iterations", 15);
  const int seed = args.get_int("seed", 1000);
  const int grid = args.get_int("grid", 3);
  const int levels = args.get_int("levels", 4);
  const int components = args.get_int("components", 10);
  const bool quiet = args.has("quiet");
  const bool adapt = !args.has("no-adapt");
  const bool perceptual_scale = !args.has("no-perceptual-scale");
  const bool full_metric = perceptual_scale && !args.has("diagonal-metric");
  app::ZoomPolicy policy =
      pixel_person ? app::zoom_policy_for_cells(cell_px, jnd_px) : app::ZoomPolicy{};
  policy.distinct_mm = args.get_double("distinct-mm", policy.distinct_mm);
  if (!(jnd_mm >= 0.0 && jnd_mm < 1e4)) throw ArgError("--jnd-mm must be in [0, 10000)");
  if (!(policy.distinct_mm >= 0.0 && policy.distinct_mm < 1e4)) {
    throw ArgError("--distinct-mm must be in [0, 10000)");
  }
  if (trials < 1 || iterations < 1) throw ArgError("--trials and --iterations must be >= 1");
  if (grid != 3 && grid != 5) throw ArgError("--grid must be 3 or 5 (the window's grids)");
  if (levels < 1 || levels > 8) throw ArgError("--levels must be between 1 and 8");
  if (components < 0) throw ArgError("--components must be >= 0 (0 = all the file has)");
  const std::string target_mode = args.get_or("target", "random");
  if (target_mode != "random") throw ArgError("--target: use random, or give --target-betas");
  sps::SearchOptions options = read_search_options(args);
  // A plane shorter than what the pixel person sees would show look-alike cells however the
  // first grid is widened: its sides are at least the threshold long, in the framing the
  // grids typically get (BodySpace::min_plane_length, the same rule).
  const double framed_pixel_mm = pixel_mm * spaces::typical_frame_scale(framing);
  if (pixel_person) {
    options.min_plane_length = std::max(options.min_plane_length, framed_pixel_mm);
  }
  options.min_plane_length = args.get_double("min-plane-mm", options.min_plane_length);
  if (!(options.min_plane_length >= 0.0 && options.min_plane_length < 1e4)) {
    throw ArgError("--min-plane-mm must be in [0, 10000)");
  }
  options.perceptual_length_scales = !args.has("no-perceptual-ls");
  options.centre_on_mean_maximum = !args.has("no-mean-centre");
  options.perceptual_btl_scale = args.get_double("perceptual-btl", options.perceptual_btl_scale);
  if (!(options.perceptual_btl_scale >= 1e-8 && options.perceptual_btl_scale <= 1e3)) {
    throw ArgError("--perceptual-btl must be in [1e-8, 1000]");
  }
  // The pixel person's choices are as noisy as the window assumes at that cell size; the mm
  // person's as their threshold says.
  options.choice_temperature_mm = args.get_double(
      "choice-temperature-mm", pixel_person ? app::choice_temperature_for_cells(cell_px, jnd_px)
                                            : app::choice_temperature_for_jnd_mm(jnd_mm));
  if (!(options.choice_temperature_mm >= 0.01 && options.choice_temperature_mm <= 1e3)) {
    throw ArgError("--choice-temperature-mm must be in [0.01, 1000]");
  }
  // Every person gets the planes the window makes for a body search (BodySpace::plane_axes),
  // unless --plane-axes says otherwise. The perfect chooser (--jnd-mm 0) too: with the regions
  // of its choices bounding the estimate they serve it best (100 trials, mean gap at plane 10
  // 4.97 mm against 6.96 on the paper's planes; without the regions it stalled at 10.9).
  if (!args.has("plane-axes")) options.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  const bool target_model = !args.has("no-target-model");
  // The window's plane size and regions of choices for bodies (spaces::body_uncertainty_size).
  use_space_uncertainty_size(args, spaces::body_uncertainty_size(), options);
  // The side a person needs to tell a deep zoom level's cells apart, as the window gives it to
  // a person of this threshold (BodySpace::uncertainty_min_side): the pixel person's as the
  // grids are typically framed, the mm person's (RMS) as the largest vertex distance it is.
  options.uncertainty_min_side =
      args.get_double("uncertainty-min-side",
                      spaces::body_uncertainty_min_side(
                          pixel_person ? framed_pixel_mm : app::kLargestPerRmsDistance * jnd_mm));
  if (!(options.uncertainty_min_side >= 0.0 && options.uncertainty_min_side < 1e4)) {
    throw ArgError("--uncertainty-min-side must be in [0, 10000)");
  }
  policy.compare_mm = args.get_double("compare-mm", policy.compare_mm);
  if (!(policy.compare_mm >= 0.0 && policy.compare_mm < 1e4)) {
    throw ArgError("--compare-mm must be in [0, 10000)");
  }
  if (args.has("zoom-factors")) {
    policy.factors = args.get_doubles("zoom-factors");
    if (policy.factors.empty()) throw ArgError("--zoom-factors: give one or more factors");
    for (double f : policy.factors) {
      if (!(f > 0.0 && f < 1.0)) throw ArgError("--zoom-factors: each factor must be in (0, 1)");
    }
  }

  const body::Model model = load_benchmark_model(args, components);
  const int k = model.component_count();
  const auto framed = std::make_shared<const spaces::FramedBodies>(model, framing);
  const body::ShapeDistance& distance = framed->distance();
  Eigen::VectorXf fixed_target;
  if (args.has("target-betas")) {
    const auto b = args.get_doubles("target-betas");
    if (b.empty() || static_cast<int>(b.size()) > k) {
      throw ArgError("--target-betas: give 1 to " + std::to_string(k) + " values");
    }
    fixed_target = Eigen::VectorXf::Zero(k);
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!std::isfinite(b[i]) || std::abs(b[i]) > 10.0) {
        throw ArgError("--target-betas: value " + std::to_string(i + 1) + " is not in [-10, 10]");
      }
      fixed_target[static_cast<Eigen::Index>(i)] = static_cast<float>(b[i]);
    }
  }
  // --hold NAME (repeatable): every grid keeps the target body's NAME (the user knows it).
  const auto hold_names = args.get_all("hold");
  std::shared_ptr<const body::Model> hold_model;
  std::set<std::string> held_once;
  for (const auto& name : hold_names) {
    if (body::find_measurement(name) == nullptr) {
      throw ArgError("--hold: unknown measurement '" + name +
                     "' (known: " + body::measurement_names() + ")");
    }
    if (!held_once.insert(name).second) throw ArgError("--hold: " + name + " is given twice");
  }
  if (!hold_names.empty()) hold_model = std::make_shared<const body::Model>(model);
  const auto clock = std::make_shared<HoldClock>();
  // The pixel person sees the grids as the window shows them, each framed to its tallest body
  // (spaces::framed_body_distance); the mm person's threshold is in millimetres of the body.
  const app::PairwiseDistance pairwise =
      pixel_person ? spaces::seen_body_distance(framed)
                   : app::PairwiseDistance([&distance](const std::vector<Eigen::VectorXd>& xs) {
                       return distance.pairwise_max_mm(xs);
                     });

  SimulationResults results(iterations, seed, true);
  for (int trial = 0; trial < trials; ++trial) {
    const auto trial_seed = static_cast<std::uint64_t>(seed + trial);
    const Eigen::VectorXf target =
        fixed_target.size() > 0 ? fixed_target : random_target(k, trial_seed);
    const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
      return distance.rms_to_betas_mm(xs, target);
    };
    // The pixel person sees how far a cell is from the body in mind as the window measures
    // look-alikes: its largest visible shift (2 px of a 230 px cell is 19 mm of the body's
    // outline at the default framing, however little of the body moves), enlarged as the grid
    // is framed. The mm person judges by the RMS distance.
    const bench::TargetDistance seen = [&](const std::vector<Eigen::VectorXd>& xs) {
      return framed->seen_to_betas_mm(xs, target);
    };
    app::SessionSettings settings;
    settings.space = "body";  // the benchmark's function (--function body), not a default
    settings.components = k;
    settings.grid_size = grid;
    settings.zoom_levels = levels;
    settings.seed = trial_seed;
    app::Session session(settings, options);
    if (hold_model) {
      std::vector<std::string> holds;
      const body::Measurements m = body::measure(model, target);
      for (const auto& name : hold_names) {
        holds.push_back(name + "=" + std::to_string(m.*(body::find_measurement(name)->field)));
      }
      session.set_constraint_projector(std::make_shared<TimedHolds>(
          spaces::make_body_holds(hold_model, holds, session.current_best()), clock));
    }
    if (perceptual_scale) {
      session.set_perceptual_scale(distance.direction_rms_mm(),
                                   full_metric ? distance.direction_gram_mm2() : Eigen::MatrixXd());
      if (target_model) session.set_population(spaces::body_population(k));
    }
    if (adapt) session.set_perceptual_distance(pairwise, policy);
    play_trial(session, to_target, pairwise, jnd_mm, clone_mm, trial_seed, results,
               pixel_person ? seen : bench::TargetDistance{});
    if (!quiet) std::cerr << "\rtrial " << (trial + 1) << "/" << trials << std::flush;
  }
  if (!quiet) std::cerr << "\n";
  if (clock->surface_calls > 0) {
    std::cerr << "holds: " << clock->surface_calls << " surface solves and normals, "
              << 1000.0 * clock->surface_seconds / clock->surface_calls
              << " ms each (the optimizer's planes and the centres shown); " << clock->cells
              << " cells projected, " << 1000.0 * clock->cell_seconds / std::max(1L, clock->cells)
              << " ms each\n";
  }

  std::ostringstream title;
  title << "# " << sps::method_name(options.method) << " on body (" << model.name << ", " << k
        << " components), user zoom-jnd (" << grid << "x" << grid << ", " << levels
        << " levels, JND " << jnd_mm << " mm";
  if (pixel_person) {
    title << " = " << jnd_px << " px in a " << cell_px << " px cell, " << framing_name
          << "; look-alikes under " << clone_mm << " mm";
  }
  title << (adapt ? "" : ", no zoom adaptation")
        << (perceptual_scale ? "" : ", no perceptual scale")
        << (perceptual_scale && !full_metric ? ", diagonal metric" : "")
        << (perceptual_scale && !target_model ? ", no target model" : "") << "), target "
        << (fixed_target.size() > 0 ? "fixed" : "random") << ", " << trials << " trials, seeds "
        << seed << "-" << (seed + trials - 1) << "; gap = RMS vertex distance (mm) of the best "
        << "body so far";
  for (std::size_t i = 0; i < hold_names.size(); ++i) {
    title << (i == 0 ? "; holding the target's " : ", ") << hold_names[i];
  }
  write_simulation_results(args, title.str(), results);
  return 0;
}

}  // namespace cli
