#include "app/cell_visibility.hpp"

#include <algorithm>

namespace app {

double millimetres_per_pixel(double cell_px) {
  return 1000.0 * kCellFrameHeightM / std::max(1.0, cell_px);
}

double look_alike_mm(double cell_px, double jnd_px) {
  return std::max(0.0, jnd_px) * millimetres_per_pixel(cell_px);
}

}  // namespace app
