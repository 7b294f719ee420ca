// `simulate`: runs sequential plane search (or a baseline) against a synthetic goodness
// function with a simulated user and prints the optimality gap and optimizer latency per
// iteration. This is the benchmark behind docs/benchmarks.md.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/simulate_body.hpp"
#include "cli/simulate_common.hpp"
#include "cli/simulate_photo.hpp"
#include "sps/plane_search.hpp"
#include "testing/simulated_user.hpp"
#include "testing/test_functions.hpp"

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
  --plane-axes A      what SPS planes span once the design in mind is estimated:
                      expected-improvement (the paper's) | uncertainty (where that estimate is
                      least certain); default: the window's (uncertainty for bodies and
                      photos; the paper's for the synthetic functions)
  --uncertainty-extent X   half-diagonals of uncertainty planes in SDs (default 5;
                      photos 3)
  --uncertainty-min-lengths N  their smallest side, in smallest plane lengths (default 2;
                      photos 1)
  --choice-region-slack K  how loosely a choice's region bounds the estimate in their
                      covariance, in choice temperatures (default: the space's, 8 for
                      bodies; -1: not at all, as photos and before 2026-12-06)
  --threads N         optimizer threads (default 2)
  --csv FILE          also write the table as CSV
  --per-trial-csv F   write every trial's gap and optimizer seconds per iteration
body benchmark (--function body): the product's own job. Each trial has a target body; a
simulated person clicks through the window's session logic (same cells, same zoom adaptation,
same submission) and cannot tell apart cells whose RMS vertex distances to the target are
within the JND of the best one (picks uniformly among them). Gap = RMS vertex distance (mm) of
the best body chosen so far; extra columns duplicate_grids (fraction of the grids clicked on
that held two bodies differing by < 5 mm at every vertex) and pinned_fraction (mean fraction of
the current best's coordinates within 1e-3 of 0 or 1). Defaults: 10 trials, 15 iterations.
  --model M           FILE (.npz) | neutral | female | male (default neutral = embedded model)
  --components K      shape components searched (default 10)
  --target random     each trial draws target betas i.i.d. N(0,1) truncated to +-2.5 (default)
  --target-betas B..  the same target for every trial (missing betas are 0)
  --user zoom-jnd     the only user here; --jnd-mm D (default 5)
  --jnd-px D          a person who resolves D pixels in a cell of --cell-px N pixels
                      (default 230, the default window's): D px = D * 2144 / N mm, used as
                      the person's threshold, the session's and the duplicate_grids count's,
                      and the planes' smallest side (--min-plane-mm) when it is larger;
                      each grid framed as the window frames it
  --framing close-ups|whole-body   with --jnd-px: grids framed on the band of the body where
                      their cells differ, as the window does by default (close-ups), or on
                      the whole body (whole-body); out of view differences count for nothing
  --grid 3|5, --levels L   the window's grid and clicks per plane
  --no-adapt          do not give the session the perceptual distance (fixed factor-2 zoom)
  --distinct-mm D     the session's smallest difference between cells (default 10)
  --no-perceptual-scale  do not tell the optimizer how much each direction changes the body
  --diagonal-metric   tell it one scale per direction only, not how directions overlap (the
                      RMS vertex distance's Gram matrix, which the window gives it)
  --min-plane-mm L    with the perceptual scale: smallest RMS length of u and v (default 12)
  --uncertainty-min-side L  the uncertainty planes' smallest side, RMS mm (default: what the
                      window gives a person of this threshold, 8 thresholds: 40 for the
                      5 mm person, 30 for the pixel person at 230 px; 0: no such bound)
  --no-perceptual-ls  do not scale the length-scale priors by it
  --no-mean-centre    centre planes on the best observed point, not the posterior-mean maximum
  --no-target-model   centre planes on the posterior-mean maximum, not on the estimate of the
                      body in mind (choices as distances to it, body population as its prior)
  --choice-temperature-mm T  that estimate's softmax temperature (default: the person's
                      threshold, --jnd-mm, or what the window assumes at --cell-px; at least 3)
  --perceptual-btl S  with the perceptual scale: the BTL temperature (default 1; plain 0.01)
  --compare-mm D      zoom-level clicks count only over cells differing by >= D mm (default 40)
  --zoom-factors F,.. zoom steps the session tries in order (default 0.7,0.8; the paper: 0.5)

photo benchmark (--function photo): the paper's photo application. Each trial has a target
edit of the picture; a simulated person clicks through the window's session logic (3x3 grids,
the same zoom adaptation in colour differences) and cannot tell apart cells whose mean
CIEDE2000 differences to the target lie within the JND of the best one. Gap = mean CIEDE2000
(on a 40-pixel copy of the picture) of the best edit chosen so far to the target; the same
columns as the body benchmark (duplicate_grids: grids with two cells closer than the session's
--distinct-delta-e, by the visible difference).
  --target T          random (default: each trial a seeded edit, every parameter N(0, 0.4) of
                      its -1..+1 range, within +-0.9) | warmer-brighter | cooler | more-contrast
  --image FILE        the picture (PNG or JPEG; default the built-in landscape)
  --jnd-delta-e D     the person's threshold (default 2.3)
  --distinct-delta-e D  the session's: no grid with two cells closer (default 3.5, the window's)
  --grid 3|5, --levels L   (default 3, 4: the window's photo grid)
  --no-adapt, --no-perceptual-scale, --no-target-model   as for the body benchmark
  --min-plane-delta-e L  smallest perceptual length of u and v (default 20, as the window)
  --compare-delta-e D    zoom-level clicks count only over cells this different (default 2 JND)
  --choice-temperature T the target estimate's softmax temperature (default 3)

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

int run(int argc, char** argv) {
  const cli::ArgParser args(
      argc, argv,
      {"help", "zoom-prefs", "quiet", "no-adapt", "no-perceptual-scale", "diagonal-metric",
       "no-perceptual-ls", "no-mean-centre", "no-target-model"},
      {"target-betas"});
  if (args.has("help")) {
    print_help();
    return 0;
  }
  if (args.get_or("function", "gaussian") == "body") return cli::run_body_simulation(args);
  if (args.get_or("function", "gaussian") == "photo") return cli::run_photo_simulation(args);
  std::set<std::string> known{"function",   "dims", "optimum",       "user",   "trials",
                              "iterations", "seed", "grid",          "levels", "resolution",
                              "zoom-prefs", "csv",  "per-trial-csv", "quiet"};
  known.insert(cli::search_option_names().begin(), cli::search_option_names().end());
  args.reject_unknown(known);
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
  sps::SearchOptions options = cli::read_search_options(args);
  if (dims < 1 || dims > sps::kMaxSearchDims) {
    throw cli::ArgError("--dims must be 1-" + std::to_string(sps::kMaxSearchDims));
  }
  options.dims = dims;
  if (user != "argmax" && user != "zoom") throw cli::ArgError("--user: use argmax or zoom");
  if (trials < 1 || iterations < 1) throw cli::ArgError("--trials and --iterations must be >= 1");
  if (grid < 3 || grid % 2 == 0) throw cli::ArgError("--grid must be odd and at least 3");
  if (levels < 1) throw cli::ArgError("--levels must be at least 1");
  if (resolution < 2) throw cli::ArgError("--resolution must be at least 2");
  // The function's own checks (its name, dimensions, optimum) are about the command line.
  const auto g = [&] {
    try {
      return sps::make_test_function(function, dims, optimum);
    } catch (const std::invalid_argument& e) {
      throw cli::ArgError(std::string("--function: ") + e.what());
    }
  }();

  cli::SimulationResults results(iterations, seed, false);
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
      results.gaps[static_cast<std::size_t>(it)].push_back(g->optimum_value() - best);
      results.seconds[static_cast<std::size_t>(it)].push_back(search.last_submit_seconds());
    }
    if (!quiet) {
      std::cerr << "\rtrial " << (trial + 1) << "/" << trials << std::flush;
    }
  }
  if (!quiet) std::cerr << "\n";

  std::ostringstream title;
  title << "# " << method_text << " on " << g->name() << " " << dims << "-D, user " << user
        << (user == "zoom"
                ? " (" + std::to_string(grid) + "x" + std::to_string(grid) + ", " +
                      std::to_string(levels) + " levels" + (zoom_prefs ? ", zoom prefs" : "") + ")"
                : "")
        << ", " << trials << " trials, seeds " << seed << "-" << (seed + trials - 1);
  cli::write_simulation_results(args, title.str(), results);
  return 0;
}

const cli::CommandRegistration kRegistration{
    "simulate", "benchmark the optimizer against synthetic functions with simulated users", &run};

}  // namespace
