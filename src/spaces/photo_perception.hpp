// What a person can see of a photo edit: colour differences in CIELAB (CIEDE2000, on a small
// copy of the picture: the edits are global, so a thousand pixels carry the picture's colour
// distribution). Two measures, as a body has its largest and its RMS vertex distance:
// - the visible difference, the mean CIEDE2000 over the tenth of the pixels that change most:
//   an edit of the highlights changes only the sky, and a person sees it there however little
//   of the picture the sky is (the mean over all pixels would call it invisible), while pixels
//   clipped to black or white by an edit change no more and do not hide the rest. The photo
//   space installs it through the same DesignSpace hook as the body's largest vertex
//   distance, so zoom adaptation, the look-alike check and the perceptual scale of the planes
//   apply to photos in Delta E units as they apply to bodies in millimetres;
// - the mean CIEDE2000 over all pixels, the benchmark's distance to a target edit.
//
// References (formulas and constants only):
// - sRGB: IEC 61966-2-1 (transfer function, D65 primaries).
// - CIELAB: CIE 15:2004, D65 white.
// - CIEDE2000: G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula:
//   implementation notes, supplementary test data, and mathematical observations", Color
//   Research & Application 30(1), 2005 (kL = kC = kH = 1).
// - The just-noticeable difference: Delta E*ab of about 2.3 (M. Mahy, L. Van Eycken,
//   A. Oosterlinck, "Evaluation of uniform color spaces developed after the adoption of CIELAB
//   and CIELUV", Color Research & Application 19(2), 1994; G. Sharma, "Digital Color Imaging
//   Handbook", 2003). CIEDE2000 rates most pairs lower than Delta E*ab, so 2.3 taken on it is a
//   conservative threshold: cells it calls different are at least that far apart.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "app/session.hpp"
#include "spaces/photo_image.hpp"

namespace spaces {

// The JND of the benchmark's person (`simulate --function photo`; Delta E, see above).
constexpr double kPhotoJndDeltaE = 2.3;

// How far apart the window keeps the cells of a grid: 3.5, where an untrained observer sees a
// clear difference (W. Mokrzycki, M. Tatol, "Color difference Delta E - a survey", Machine
// Graphics and Vision 20(4), 2011: 2-3.5 noticed by an inexperienced observer, 3.5-5 a clear
// difference). One JND is what a person notices between two large patches side by side; in a
// grid of thumbnails (136-230 px at the default window), cells one JND apart were hard to
// tell apart when looked at, so the grid keeps them a clear difference apart.
constexpr double kPhotoDistinctDeltaE = 3.5;

// The smallest length of a plane's sides (perceptual scale units, Delta E) for photos. The
// scale adds the parameters' visible changes as if they were independent, which they are not
// (the three colour-balance bands overlap in tone, and edits clip at the box's corners), so a
// plane of the optimizer's default length (12) often held neighbouring cells closer than the
// grid allows at its edges; at 20 the photo benchmark shows none on 3x3 grids
// (docs/benchmarks.md).
constexpr double kPhotoMinPlaneDeltaE = 20.0;

// With uncertainty planes (the window's, sps::PlaneAxes::kTargetUncertainty): their sides at
// least one smallest plane length long (the bodies' 3 lengths would ask for 60 Delta E, which
// most edits of the box cannot show). Photo benchmark, docs/benchmarks.md.
constexpr double kPhotoUncertaintyMinLengths = 1.0;
// ... and their half-diagonals 3 standard deviations of the estimate, not the bodies' 5. On the
// built-in picture the smallest length then decides every plane (at 2 the benchmark's runs are
// the same to the last digit), the first one included, which at 5 reaches far beyond the box:
// 43 % of plane 1's cells (all zoom levels) clamped at an end of a range, against 16 % at 3,
// and a few first grids that cannot be told apart (at most 0.7 % of a plane's grids; at 3 none
// on three of the four tasks). The gaps are the same on 60 people (mean Delta E at plane 10,
// summed over the four targets: 7.86 at 3, 7.91 at 5). Photo benchmark, docs/benchmarks.md.
constexpr double kPhotoUncertaintyExtent = 3.0;
// Both, as the photo space asks for them (PhotoSpace::uncertainty_size; simulate's photo runs).
inline sps::UncertaintyPlaneSize photo_uncertainty_size() {
  return {kPhotoUncertaintyExtent, kPhotoUncertaintyMinLengths};
}

// The session's zoom rules for photos, in Delta E where a body's are in millimetres: no grid
// shown holds two edits closer than `distinct` and no zoom step makes neighbours closer than
// it; a zoom-level click counts as preferred only over cells at least twice that far from it.
app::ZoomPolicy photo_zoom_policy(double distinct = kPhotoDistinctDeltaE);

// Where edits typically lie: near "no edit" (x = 0.5), each parameter spread by a fifth of the
// box (+-0.4 of its -1..+1 range for one SD): most edits people keep are moderate.
sps::Population photo_population();

struct Lab {
  double l = 0.0;
  double a = 0.0;
  double b = 0.0;
};

// sRGB channels in [0,1] (clamped) to CIELAB under D65.
Lab srgb_to_lab(const std::array<float, 3>& rgb);

// CIEDE2000 colour difference (kL = kC = kH = 1). Symmetric, 0 for equal colours.
double ciede2000(const Lab& x, const Lab& y);

// The share of the pixels (those that change most) a visible difference averages over.
constexpr double kVisibleShare = 0.1;

// Colour differences between two edits of one picture.
class PhotoDistance {
 public:
  // `image`: the picture edited (any size; a copy of at most `max_edge` pixels a side is kept).
  explicit PhotoDistance(const Image& image, int max_edge = 40);

  int pixels() const { return static_cast<int>(rgb_.size()); }

  // The edited small picture of search point x (x in [0,1]^12) in CIELAB.
  std::vector<Lab> lab_of(const Eigen::VectorXd& x) const;
  // Mean CIEDE2000 over the pixels of two pictures from lab_of().
  static double mean_difference(const std::vector<Lab>& p, const std::vector<Lab>& q);
  // Mean CIEDE2000 over the kVisibleShare of the pixels that differ most.
  static double visible_difference(const std::vector<Lab>& p, const std::vector<Lab>& q);

  // Entry (i, j): the visible difference between the edits xs[i] and xs[j]
  // (app::PairwiseDistance).
  Eigen::MatrixXd pairwise(const std::vector<Eigen::VectorXd>& xs) const;
  // Mean Delta E of each edit to the edit `target`.
  std::vector<double> to_target(const std::vector<Eigen::VectorXd>& xs,
                                const Eigen::VectorXd& target) const;
  // How much each parameter changes the picture over its range: the visible difference
  // between its two ends, the other parameters at "no edit" (the optimizer's perceptual scale).
  Eigen::VectorXd direction_scale() const;

 private:
  std::vector<std::array<float, 3>> rgb_;  // the small picture, channels in [0,1]
};

}  // namespace spaces
