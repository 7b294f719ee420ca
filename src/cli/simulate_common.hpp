// What the synthetic-function and the body benchmarks of `simulate` share: the optimizer's
// options and the tables printed and written (summary CSV, per-trial CSV).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "app/session.hpp"
#include "bench/simulated_person.hpp"
#include "cli/arg_parser.hpp"
#include "sps/plane_search.hpp"

namespace cli {

// Options every simulate run accepts (the optimizer's); the rest are the command's own.
const std::set<std::string>& search_option_names();
// --method, --threads, --current-best and the model settings; throws ArgError on bad values.
sps::SearchOptions read_search_options(const ArgParser& args);
// The design space's uncertainty plane size (as the window's planes get it), for each of its
// values not given on the command line; throws ArgError on a bad value.
void use_space_uncertainty_size(const ArgParser& args, const sps::UncertaintyPlaneSize& size,
                                sps::SearchOptions& options);

struct SimulationResults {
  int first_seed = 0;
  // [iteration][trial]
  std::vector<std::vector<double>> gaps;
  std::vector<std::vector<double>> seconds;
  // The gap of what the window would save after each plane (the session's current best once
  // the next plane is shown), and of the cell picked last: the best chosen so far in `gaps` is
  // known only to the benchmark, which knows the target.
  std::vector<std::vector<double>> saved_gaps;
  std::vector<std::vector<double>> last_pick_gaps;
  // Cells shown and, of those, cells with a parameter at the edge of its range (clamped).
  std::vector<std::vector<double>> cells;
  std::vector<std::vector<double>> edge_cells;
  // Body benchmark only (empty otherwise): grids shown with look-alike cells and grids shown,
  // and the pinned fraction of the current best, [iteration][trial].
  std::vector<std::vector<double>> look_alike_grids;
  std::vector<std::vector<double>> grids;
  std::vector<std::vector<double>> pinned;

  explicit SimulationResults(int iterations, int seed, bool body);
  bool body() const { return !pinned.empty(); }
};

// One trial of the body or photo benchmark: the simulated person (bench::play_plane_jnd, its
// own random stream from `trial_seed`) plays `results`' iterations on `session`, each plane
// recorded as the best gap so far, the gaps of the last pick and of what the window would save
// (the session's current best once the next plane is shown), the optimizer's time, the grids
// and look-alike grids shown (closer than `clone` by `look_alikes`), the cells shown and those
// clamped at an edge of the box, and the pinned fraction of the current best. The
// person judges the cells by `seen` (their visible distance to the target) when given, else by
// `to_target`, which is always the gap.
void play_trial(app::Session& session, const bench::TargetDistance& to_target,
                const app::PairwiseDistance& look_alikes, double jnd, double clone,
                std::uint64_t trial_seed, SimulationResults& results,
                const bench::TargetDistance& seen = {});

// Prints the table (after `title`) and writes --csv / --per-trial-csv when asked.
void write_simulation_results(const ArgParser& args, const std::string& title,
                              const SimulationResults& results);

}  // namespace cli
