// How a grid of bodies is framed in its cells and how different its cells look there: the
// window draws each grid with grid_frame(), its look-alike test and zoom use the distance as
// seen(), and the body benchmark's pixel person judges cells with the same two (no GL here).
// Two framings: the whole body, framed to the grid's tallest body (app::cell_frame_scale), and
// close-ups, where a grid whose bodies differ only in a band of heights (body::GridFraming:
// after the first zoom mostly the trunk's girths) is framed on that band, which shows its
// differences up to twice as large; the differences outside the band are out of view and
// count for nothing.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "app/cell_visibility.hpp"
#include "app/design_space.hpp"
#include "body/body_model.hpp"
#include "body/grid_framing.hpp"
#include "body/shape_distance.hpp"
#include "body/standing_height.hpp"

namespace spaces {

enum class BodyFraming { kWholeBody, kCloseUps };

// A close-up from mid-thigh to the top of the tallest head, about 1.3 m of the default frame's
// 2.16 m: what most grids after the first zoom are framed at.
constexpr double kCloseUpScale = 0.6;

// The scale a grid is typically framed at, before its points are known (the planes' smallest
// side is chosen with it): 1 for the whole body (a grid of 1.98 m people), kCloseUpScale for
// close-ups.
double typical_frame_scale(BodyFraming framing);

class FramedBodies {
 public:
  // Throws std::invalid_argument for a model without vertices or mismatched shape directions.
  FramedBodies(const body::Model& model, BodyFraming framing);

  BodyFraming framing() const { return framing_; }
  double typical_scale() const { return typical_frame_scale(framing_); }
  const body::ShapeDistance& distance() const { return distance_; }

  // The camera framing of a grid of these points.
  app::GridFrame grid_frame(const std::vector<Eigen::VectorXd>& xs) const;
  // The largest vertex distance between each pair of cells that the grid's framing shows, in
  // mm at the default framing (divided by its scale): what the look-alike test compares.
  Eigen::MatrixXd seen_pairwise_mm(const std::vector<Eigen::VectorXd>& xs) const;
  // The same from each cell to the body with the given betas, as the grid of xs shows it.
  std::vector<double> seen_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                       const Eigen::VectorXf& target_betas) const;

 private:
  struct View {
    app::GridFrame frame;
    std::vector<int> vertices;  // in view; empty: all
  };
  View view(const std::vector<Eigen::VectorXd>& xs) const;

  BodyFraming framing_;
  body::ShapeDistance distance_;
  body::GridFraming bands_;
};

// The session's perceptual-distance hook on `bodies` (seen_pairwise_mm). The hook holds them,
// so a session copied into the redo stack stays valid after the space is replaced.
app::PairwiseDistance seen_body_distance(std::shared_ptr<const FramedBodies> bodies);

}  // namespace spaces
