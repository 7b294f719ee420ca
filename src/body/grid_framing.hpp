// Which part of the bodies a grid's cells show. A cell a person sees is a couple of hundred
// pixels high: framed on the whole body (2 m), 2 px are about 19 mm, more than the bodies of a
// zoomed-in grid differ by. Once the nine bodies of a grid differ only in a part of the body
// (after the first zoom, mostly the trunk's girths), the cells can show that part larger: the
// band of heights where the bodies differ most, never shorter than a trunk, so the whole
// difference the grid is about stays in view and is seen twice as large. This module finds the
// band and which vertices it holds; the camera that shows it is the app's (cell_visibility).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"
#include "body/standing_height.hpp"

namespace body {

// Heights (m) above the floor under the grid's middle body (its lowest vertex).
struct HeightBand {
  double bottom_m = 0.0;
  double top_m = 0.0;
  double height_m() const { return top_m - bottom_m; }
};

struct BandRule {
  // Vertices whose displacement across the grid is at least this share of the largest one are
  // what the grid is about: the band holds them all.
  double share = 0.7;
  // The shortest band shown (m), from the top of the tallest head down: the head and the
  // trunk, so that a person still sees a body and not a patch of skin.
  double min_height_m = 1.0;
  double margin_m = 0.05;  // around the vertices the band must hold
  // A band reaching below this share of the body's height (the shins) is taken to the floor.
  double feet_share = 0.25;
};

// A grid's band and what lies in it, from one evaluation of the points' mean body.
struct FramedBand {
  HeightBand band;
  std::vector<int> vertices;  // of the points' mean body inside the band (indices, ascending)
  double tallest_m = 0.0;     // the tallest of the points' bodies (lowest to highest vertex)
};

class GridFraming {
 public:
  // Uses the model's kept components (search points x in [0, 1], beta = 6x - 3). Throws
  // std::invalid_argument for a model without vertices or with mismatched shape directions.
  explicit GridFraming(const Model& model);
  int dims() const { return static_cast<int>(unit_dirs_.cols()); }
  // How tall the points' bodies stand (the band's top is the tallest head).
  const StandingHeights& heights() const { return heights_; }
  // The band of heights on the points' mean body from rule.margin_m above the tallest of their
  // heads down to rule.margin_m below the lowest vertex that moves at least rule.share of the
  // most any vertex moves across the points, at least rule.min_height_m high, taken to the
  // floor past rule.feet_share of the height. The whole body [-margin, tallest + margin] when
  // that band reaches the floor (or for fewer than two points, or points that do not differ).
  // Heights are above the floor under the mean body (its lowest vertex).
  FramedBand frame(const std::vector<Eigen::VectorXd>& xs, const BandRule& rule = {}) const;
  HeightBand band(const std::vector<Eigen::VectorXd>& xs, const BandRule& rule = {}) const {
    return frame(xs, rule).band;
  }

 private:
  HeightBand band_on(const Eigen::VectorXf& heights, double tallest_m,
                     const std::vector<Eigen::VectorXd>& xs, const BandRule& rule) const;

  StandingHeights heights_;
  Eigen::VectorXf template_;   // 3V: the body at x = 0 (all coefficients at -3 SD)
  Eigen::MatrixXf unit_dirs_;  // 3V x K: d vertices / d x (m)
};

}  // namespace body
