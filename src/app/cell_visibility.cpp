#include "app/cell_visibility.hpp"

#include <algorithm>
#include <cmath>

#include "app/session.hpp"

namespace app {

double cell_frame_scale(double tallest_m) {
  if (!(tallest_m > 0.0)) return 1.0;
  return std::clamp((tallest_m + kCellHeadroomM) / kCellFrameTopM, 0.5, 1.0);
}

GridFrame cell_frame_for_band(double bottom_m, double top_m) {
  const double shown = top_m - bottom_m;
  if (!std::isfinite(bottom_m) || !std::isfinite(top_m) || !(shown > 0.0)) return {};
  const double scale = std::clamp(shown / (kCellFrameTopM - kCellFrameBottomM), 0.25, 1.0);
  if (scale > 1.0 - 1e-9) return {};
  // The camera scaled by s about height p shows height y where the default shows
  // p + (y - p) / s: the band's bottom lands on the frame's, p = (bottom - s b0) / (1 - s).
  return {scale, (bottom_m - scale * kCellFrameBottomM) / (1.0 - scale)};
}

double millimetres_per_pixel(double cell_px) {
  return 1000.0 * kCellFrameHeightM / std::max(1.0, cell_px);
}

double look_alike_mm(double cell_px, double jnd_px) {
  return std::max(0.0, jnd_px) * millimetres_per_pixel(cell_px);
}

double choice_temperature_for_cells(double cell_px, double jnd_px) {
  return std::max(kChoiceTemperatureMm, look_alike_mm(cell_px, jnd_px) / kLargestPerRmsDistance);
}

double choice_temperature_for_jnd_mm(double jnd_rms_mm) {
  return std::isfinite(jnd_rms_mm) ? std::max(kChoiceTemperatureMm, jnd_rms_mm)
                                   : kChoiceTemperatureMm;
}

ZoomPolicy zoom_policy_for_cells(double cell_px, double jnd_px) {
  ZoomPolicy policy;
  policy.distinct_mm = std::max(kCloneMm, look_alike_mm(cell_px, jnd_px));
  policy.look_alike_mm = policy.distinct_mm;
  return policy;
}

}  // namespace app
