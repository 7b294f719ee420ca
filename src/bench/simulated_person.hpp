// The simulated person of the body benchmark (`simulate --function body --user zoom-jnd`) and
// the statistics it reports. The user clicks through app::Session, exactly as the window
// does, so the benchmark measures the product: the same cells (clamping, zoom adaptation),
// the same submission (zoom-level preferences included), the same worker.
#pragma once

#include <functional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "app/session.hpp"

namespace bench {

// Distance (mm) of each search point's body to the body the user has in mind.
using TargetDistance = std::function<std::vector<double>(const std::vector<Eigen::VectorXd>&)>;

// A user who cannot tell apart cells whose distances to the target are within `jnd_mm` of the
// best one: the index of a cell drawn uniformly among those. Throws on an empty list.
int jnd_pick(const std::vector<double>& distance_mm, double jnd_mm, std::mt19937_64& rng);

// True when two cells of a grid are look-alikes: their bodies differ by less than `clone_mm`
// at every vertex (pairwise largest vertex distances, as PairwiseDistance returns them).
bool has_look_alikes(const Eigen::MatrixXd& pairwise_mm, double clone_mm = app::kCloneMm);

// Fraction of the coordinates of x within `tolerance` of 0 or 1 (pinned on the box).
double pinned_fraction(const Eigen::VectorXd& x, double tolerance = 1e-3);

struct PlaneOutcome {
  Eigen::VectorXd chosen;    // the submitted choice
  int grids = 0;             // grids the user clicked on
  int look_alike_grids = 0;  // of those, grids with look-alike cells
  int cells = 0;             // cells on those grids
  int edge_cells = 0;        // of those, cells with a parameter at the edge of its range
  double optimizer_seconds = 0.0;
};

// One plane: the user clicks until the session submits, the submission runs on the window's
// worker, and the session moves on to the next plane. `look_alikes` measures the grids shown
// (it need not be the session's own distance hook). Throws if the optimizer fails.
// Grids count as look-alike grids when two cells differ by less than `clone_mm`.
PlaneOutcome play_plane_jnd(app::Session& session, const TargetDistance& to_target,
                            const app::PairwiseDistance& look_alikes, double jnd_mm,
                            std::mt19937_64& rng, double clone_mm = app::kCloneMm);

}  // namespace bench
