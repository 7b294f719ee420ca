// `simulate`: runs sequential plane search (or a baseline) against a synthetic goodness
// function with a simulated user and prints the optimality gap and optimizer latency per
// iteration. This is the benchmark behind docs/benchmarks.md.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "sps/plane_search.hpp"
#include "testing/simulated_user.hpp"
#include "testing/test_functions.hpp"
#include "util/atomic_file.hpp"

namespace {

void print_help() {
  std::cout <<
      R"(usage: sequential-gallery simulate [options]

Runs trials of a search method against a synthetic goodness function with a simulated user
and prints, per iteration, the mean, SD (divided by n) and median optimality gap (best value
possible minus the best value chosen so far) and the median seconds the optimizer spent
absorbing a choice and proposing the next plane.

options:
  --function NAME     goodness function (default gaussian); see the list below
  --dims N            dimensions (default 5)
  --optimum X         put the optimum at (X, ..., X) where the function allows
  --method M          sps | sps-random | sls (default sps)
  --user U            argmax: dense search over the whole plane/line (paper's experiment)
                      zoom: greedy clicks on an n x n zoomable grid (what a person can do)
                      (default argmax)
  --trials N          trials (default 10); trial i uses seed + i
  --iterations N      iterations per trial (default 25)
  --seed S            first seed (default 1000)
  --grid N            zoom user: grid size, odd (default 3)
  --levels L          zoom user: zoom levels per plane (default 4)
  --resolution R      argmax user: lattice resolution (default 640, as the reference)
  --zoom-prefs        zoom user: also submit every level's click as preference data
  --current-best C    posterior-mean | last-selection (default posterior-mean)
  --threads N         optimizer threads (default 2)
  --csv FILE          also write the table as CSV
  --per-trial-csv F   write every trial's gap and optimizer seconds per iteration
model settings (defaults are the paper's):
  --amplitude-prior A, --length-scale-prior L, --prior-log-variance V, --btl-scale S,
  --noise-variance B, --plane-restarts N, --ei-starts N, --representatives 5|9
  --quiet             no progress on stderr

functions:
)";
  for (const auto& f : sps::available_functions()) {
    std::cout << "  " << std::left << std::setw(18) << f.name << f.description << "\n";
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {"help", "zoom-prefs", "quiet"});
  if (args.has("help")) {
    print_help();
    return 0;
  }
  args.reject_unknown({"function",
                       "dims",
                       "optimum",
                       "method",
                       "user",
                       "trials",
                       "iterations",
                       "seed",
                       "grid",
                       "levels",
                       "resolution",
                       "zoom-prefs",
                       "current-best",
                       "threads",
                       "csv",
                       "per-trial-csv",
                       "quiet",
                       "amplitude-prior",
                       "length-scale-prior",
                       "prior-log-variance",
                       "btl-scale",
                       "noise-variance",
                       "plane-restarts",
                       "ei-starts",
                       "representatives"});
  const std::string function = args.get_or("function", "gaussian");
  const int dims = args.get_int("dims", 5);
  const double optimum = args.get_double("optimum", std::numeric_limits<double>::quiet_NaN());
  const std::string method_text = args.get_or("method", "sps");
  const std::string user = args.get_or("user", "argmax");
  const int trials = args.get_int("trials", 10);
  const int iterations = args.get_int("iterations", 25);
  const int seed = args.get_int("seed", 1000);
  const int grid = args.get_int("grid", 3);
  const int levels = args.get_int("levels", 4);
  const int resolution = args.get_int("resolution", 640);
  const bool zoom_prefs = args.has("zoom-prefs");
  const bool quiet = args.has("quiet");

  sps::SearchOptions options;
  options.dims = dims;
  options.threads = args.get_int("threads", 2);
  if (!sps::parse_method(method_text, options.method)) {
    throw cli::ArgError("--method: '" + method_text + "' is not sps, sps-random or sls");
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
    throw cli::ArgError("model settings must be positive");
  }
  const std::string best_text = args.get_or("current-best", "posterior-mean");
  if (best_text == "last-selection") {
    options.current_best = sps::CurrentBest::kLastSelection;
  } else if (best_text != "posterior-mean") {
    throw cli::ArgError("--current-best: use posterior-mean or last-selection");
  }
  if (user != "argmax" && user != "zoom") throw cli::ArgError("--user: use argmax or zoom");
  if (trials < 1 || iterations < 1) throw cli::ArgError("--trials and --iterations must be >= 1");
  if (grid < 3 || grid % 2 == 0) throw cli::ArgError("--grid must be odd and at least 3");
  if (levels < 1) throw cli::ArgError("--levels must be at least 1");
  if (resolution < 2) throw cli::ArgError("--resolution must be at least 2");
  const auto g = sps::make_test_function(function, dims, optimum);

  // gap[i][t], seconds[i][t]
  std::vector<std::vector<double>> gaps(static_cast<std::size_t>(iterations));
  std::vector<std::vector<double>> seconds(static_cast<std::size_t>(iterations));
  for (int trial = 0; trial < trials; ++trial) {
    options.seed = static_cast<std::uint64_t>(seed + trial);
    sps::PlaneSearch search(options);
    double best = -std::numeric_limits<double>::infinity();
    for (int it = 0; it < iterations; ++it) {
      const sps::UserAnswer answer = user == "argmax"
                                         ? sps::argmax_user(*g, search.current_plane(), resolution)
                                         : sps::zoom_user(*g, search.current_plane(), grid, levels);
      best = std::max(best, (*g)(answer.chosen));
      if (zoom_prefs) {
        search.submit(answer.chosen, answer.comparisons);
      } else {
        search.submit(answer.chosen);
      }
      gaps[static_cast<std::size_t>(it)].push_back(g->optimum_value() - best);
      seconds[static_cast<std::size_t>(it)].push_back(search.last_submit_seconds());
    }
    if (!quiet) {
      std::cerr << "\rtrial " << (trial + 1) << "/" << trials << std::flush;
    }
  }
  if (!quiet) std::cerr << "\n";

  if (const auto path = args.get("per-trial-csv")) {
    std::ostringstream out;  // written atomically below
    out << "trial,seed,iteration,gap_best_so_far,optimizer_seconds\n" << std::setprecision(17);
    for (int trial = 0; trial < trials; ++trial) {
      for (int it = 0; it < iterations; ++it) {
        out << trial << "," << (seed + trial) << "," << (it + 1) << ","
            << gaps[static_cast<std::size_t>(it)][static_cast<std::size_t>(trial)] << ","
            << seconds[static_cast<std::size_t>(it)][static_cast<std::size_t>(trial)] << "\n";
      }
    }
    util::write_file_atomically(*path, out.str());
  }
  const auto csv_path = args.get("csv");
  std::ostringstream csv;  // written atomically at the end
  if (csv_path) {
    csv << "iteration,mean_gap,sd_gap,median_gap,mean_optimizer_seconds,median_optimizer_seconds\n";
  }
  std::cout << "# " << method_text << " on " << g->name() << " " << dims << "-D, user " << user
            << (user == "zoom" ? " (" + std::to_string(grid) + "x" + std::to_string(grid) + ", " +
                                     std::to_string(levels) + " levels" +
                                     (zoom_prefs ? ", zoom prefs" : "") + ")"
                               : "")
            << ", " << trials << " trials, seeds " << seed << "-" << (seed + trials - 1) << "\n";
  std::cout << "iteration  mean_gap      sd_gap        median_gap    median_seconds\n";
  for (int it = 0; it < iterations; ++it) {
    const auto& v = gaps[static_cast<std::size_t>(it)];
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double var = 0.0;
    for (double x : v) var += (x - mean) * (x - mean);
    const double sd = std::sqrt(var / static_cast<double>(v.size()));
    const double med = median(v);
    const double sec = median(seconds[static_cast<std::size_t>(it)]);
    std::cout << std::setw(9) << (it + 1) << "  " << std::scientific << std::setprecision(4) << mean
              << "    " << sd << "    " << med << "    " << std::fixed << std::setprecision(4)
              << sec << "\n";
    if (csv_path) {
      const auto& secs = seconds[static_cast<std::size_t>(it)];
      double mean_sec = 0.0;
      for (double x : secs) mean_sec += x;
      mean_sec /= static_cast<double>(secs.size());
      csv << (it + 1) << "," << std::setprecision(10) << std::scientific << mean << "," << sd << ","
          << med << "," << mean_sec << "," << sec << "\n";
    }
  }
  if (csv_path) util::write_file_atomically(*csv_path, csv.str());
  return 0;
}

const cli::CommandRegistration kRegistration{
    "simulate", "benchmark the optimizer against synthetic functions with simulated users", &run};

}  // namespace
