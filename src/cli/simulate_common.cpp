#include "cli/simulate_common.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.hpp"

namespace cli {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double mean(const std::vector<double>& v) {
  double total = 0.0;
  for (double x : v) total += x;
  return v.empty() ? std::numeric_limits<double>::quiet_NaN()
                   : total / static_cast<double>(v.size());
}

double sum(const std::vector<double>& v) {
  double total = 0.0;
  for (double x : v) total += x;
  return total;
}

// The uncertainty planes' size as the command line or the space gave it, checked by the
// search's own rule (sps::validate_uncertainty_size) and reported as a bad argument.
void check_uncertainty_size(const sps::SearchOptions& options) {
  try {
    sps::validate_uncertainty_size(sps::uncertainty_size(options));
  } catch (const std::invalid_argument& e) {
    throw ArgError(std::string(e.what()) +
                   " (--uncertainty-extent, --uncertainty-min-lengths, --choice-region-slack)");
  }
}

}  // namespace

const std::set<std::string>& search_option_names() {
  static const std::set<std::string> names{"method",
                                           "current-best",
                                           "threads",
                                           "amplitude-prior",
                                           "length-scale-prior",
                                           "prior-log-variance",
                                           "btl-scale",
                                           "noise-variance",
                                           "plane-restarts",
                                           "ei-starts",
                                           "representatives",
                                           "plane-axes",
                                           "uncertainty-extent",
                                           "uncertainty-min-lengths",
                                           "choice-region-slack"};
  return names;
}

sps::SearchOptions read_search_options(const ArgParser& args) {
  sps::SearchOptions options;
  const std::string method_text = args.get_or("method", "sps");
  options.threads = args.get_int("threads", 2);
  if (!sps::parse_method(method_text, options.method)) {
    throw ArgError("--method: '" + method_text + "' is not sps, sps-random or sls");
  }
  options.model.amplitude_prior = args.get_double("amplitude-prior", options.model.amplitude_prior);
  options.model.length_scale_prior =
      args.get_double("length-scale-prior", options.model.length_scale_prior);
  options.model.prior_log_variance =
      args.get_double("prior-log-variance", options.model.prior_log_variance);
  options.model.btl_scale = args.get_double("btl-scale", options.model.btl_scale);
  options.model.noise_variance = args.get_double("noise-variance", options.model.noise_variance);
  options.plane_restarts = args.get_int("plane-restarts", options.plane_restarts);
  options.ei_restarts = args.get_int("ei-starts", options.ei_restarts);
  options.representatives = args.get_int("representatives", options.representatives);
  if (!(options.model.amplitude_prior > 0 && options.model.length_scale_prior > 0 &&
        options.model.prior_log_variance > 0 && options.model.btl_scale > 0 &&
        options.model.noise_variance > 0)) {
    throw ArgError("model settings must be positive");
  }
  const std::string axes_text = args.get_or("plane-axes", "expected-improvement");
  if (!sps::parse_plane_axes(axes_text, options.plane_axes)) {
    throw ArgError("--plane-axes: use expected-improvement or uncertainty");
  }
  options.uncertainty_extent = args.get_double("uncertainty-extent", options.uncertainty_extent);
  options.uncertainty_min_lengths =
      args.get_double("uncertainty-min-lengths", options.uncertainty_min_lengths);
  options.choice_region_slack = args.get_double("choice-region-slack", options.choice_region_slack);
  check_uncertainty_size(options);
  {
    // Every option read here by the search's own rule (sps::validate_options), as a bad
    // argument; the dimension comes later, from --dims or the design space.
    sps::SearchOptions read = options;
    read.dims = 1;
    try {
      sps::validate_options(read);
    } catch (const std::invalid_argument& e) {
      throw ArgError(std::string("search options: ") + e.what());
    }
  }
  const std::string best_text = args.get_or("current-best", "posterior-mean");
  if (best_text == "last-selection") {
    options.current_best = sps::CurrentBest::kLastSelection;
  } else if (best_text != "posterior-mean") {
    throw ArgError("--current-best: use posterior-mean or last-selection");
  }
  return options;
}

void use_space_uncertainty_size(const ArgParser& args, const sps::UncertaintyPlaneSize& size,
                                sps::SearchOptions& options) {
  if (!args.has("uncertainty-extent")) options.uncertainty_extent = size.extent;
  if (!args.has("uncertainty-min-lengths")) options.uncertainty_min_lengths = size.min_lengths;
  if (!args.has("choice-region-slack")) options.choice_region_slack = size.region_slack;
  check_uncertainty_size(options);
}

void play_trial(app::Session& session, const bench::TargetDistance& to_target,
                const app::PairwiseDistance& look_alikes, double jnd, double clone,
                std::uint64_t trial_seed, SimulationResults& results,
                const bench::TargetDistance& seen) {
  std::mt19937_64 user_rng(trial_seed ^ 0x757365722D726E67ULL);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < results.gaps.size(); ++i) {
    const bench::PlaneOutcome plane =
        bench::play_plane_jnd(session, seen ? seen : to_target, look_alikes, jnd, user_rng, clone);
    const double picked = to_target({plane.chosen}).front();
    best = std::min(best, picked);
    results.gaps[i].push_back(best);
    results.last_pick_gaps[i].push_back(picked);
    results.saved_gaps[i].push_back(to_target({session.current_best()}).front());
    results.cells[i].push_back(plane.cells);
    results.edge_cells[i].push_back(plane.edge_cells);
    results.seconds[i].push_back(plane.optimizer_seconds);
    results.look_alike_grids[i].push_back(plane.look_alike_grids);
    results.grids[i].push_back(plane.grids);
    results.pinned[i].push_back(bench::pinned_fraction(session.current_best()));
  }
}

SimulationResults::SimulationResults(int iterations, int seed, bool body)
    : first_seed(seed),
      gaps(static_cast<std::size_t>(iterations)),
      seconds(static_cast<std::size_t>(iterations)),
      saved_gaps(static_cast<std::size_t>(iterations)),
      last_pick_gaps(static_cast<std::size_t>(iterations)),
      cells(static_cast<std::size_t>(iterations)),
      edge_cells(static_cast<std::size_t>(iterations)) {
  if (body) {
    look_alike_grids.resize(static_cast<std::size_t>(iterations));
    grids.resize(static_cast<std::size_t>(iterations));
    pinned.resize(static_cast<std::size_t>(iterations));
  }
}

void write_simulation_results(const ArgParser& args, const std::string& title,
                              const SimulationResults& r) {
  const std::size_t iterations = r.gaps.size();
  const std::size_t trials = iterations == 0 ? 0 : r.gaps.front().size();
  // The synthetic functions have no window whose save could be measured.
  const bool with_saved = trials > 0 && r.saved_gaps.front().size() == trials;
  if (const auto path = args.get("per-trial-csv")) {
    std::ostringstream out;  // written atomically below
    out << "trial,seed,iteration,gap_best_so_far,optimizer_seconds"
        << (r.body() ? ",look_alike_grids,grids,pinned_fraction" : "")
        << (with_saved ? ",saved_gap,last_pick_gap,cells,edge_cells" : "") << "\n"
        << std::setprecision(17);
    for (std::size_t trial = 0; trial < trials; ++trial) {
      for (std::size_t it = 0; it < iterations; ++it) {
        out << trial << "," << (r.first_seed + static_cast<int>(trial)) << "," << (it + 1) << ","
            << r.gaps[it][trial] << "," << r.seconds[it][trial];
        if (r.body()) {
          out << "," << r.look_alike_grids[it][trial] << "," << r.grids[it][trial] << ","
              << r.pinned[it][trial];
        }
        if (with_saved) {
          out << "," << r.saved_gaps[it][trial] << "," << r.last_pick_gaps[it][trial] << ","
              << r.cells[it][trial] << "," << r.edge_cells[it][trial];
        }
        out << "\n";
      }
    }
    util::write_file_atomically(*path, out.str());
  }
  const auto csv_path = args.get("csv");
  std::ostringstream csv;  // written atomically at the end
  if (csv_path) {
    csv << "iteration,mean_gap,sd_gap,median_gap,mean_optimizer_seconds,median_optimizer_seconds"
        << (r.body() ? ",duplicate_grids,pinned_fraction" : "")
        << (with_saved ? ",mean_saved_gap,median_saved_gap,mean_last_pick_gap,median_last_pick_gap,"
                         "edge_cells"
                       : "")
        << "\n";
  }
  std::cout << title << "\n";
  std::cout << "iteration  mean_gap      sd_gap        median_gap    median_seconds"
            << (r.body() ? "  duplicate_grids  pinned_fraction" : "")
            << (with_saved ? "  median_saved  median_last_pick  edge_cells" : "") << "\n";
  for (std::size_t it = 0; it < iterations; ++it) {
    const auto& v = r.gaps[it];
    const double m = mean(v);
    double var = 0.0;
    for (double x : v) var += (x - m) * (x - m);
    const double sd = std::sqrt(var / static_cast<double>(v.size()));
    const double med = median(v);
    const double sec = median(r.seconds[it]);
    double duplicates = 0.0, pinned = 0.0;
    if (r.body()) {
      const double shown = sum(r.grids[it]);
      duplicates = shown > 0.0 ? sum(r.look_alike_grids[it]) / shown : 0.0;
      pinned = mean(r.pinned[it]);
    }
    std::cout << std::setw(9) << (it + 1) << "  " << std::scientific << std::setprecision(4) << m
              << "    " << sd << "    " << med << "    " << std::fixed << std::setprecision(4)
              << sec;
    if (r.body()) {
      std::cout << "    " << std::setw(13) << duplicates << "  " << std::setw(15) << pinned;
    }
    const double shown_cells = with_saved ? sum(r.cells[it]) : 0.0;
    const double edges = shown_cells > 0.0 ? sum(r.edge_cells[it]) / shown_cells : 0.0;
    if (with_saved) {
      std::cout << std::scientific << std::setprecision(4) << "  " << median(r.saved_gaps[it])
                << "    " << median(r.last_pick_gaps[it]) << "        " << std::fixed
                << std::setprecision(4) << edges;
    }
    std::cout << "\n";
    if (csv_path) {
      csv << (it + 1) << "," << std::setprecision(10) << std::scientific << m << "," << sd << ","
          << med << "," << mean(r.seconds[it]) << "," << sec;
      if (r.body()) csv << "," << duplicates << "," << pinned;
      if (with_saved) {
        csv << "," << mean(r.saved_gaps[it]) << "," << median(r.saved_gaps[it]) << ","
            << mean(r.last_pick_gaps[it]) << "," << median(r.last_pick_gaps[it]) << "," << edges;
      }
      csv << "\n";
    }
  }
  if (csv_path) util::write_file_atomically(*csv_path, csv.str());
}

}  // namespace cli
