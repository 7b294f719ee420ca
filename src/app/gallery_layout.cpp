#include "app/gallery_layout.hpp"

#include <algorithm>
#include <cmath>

namespace app {

GalleryLayout compute_layout(float width, float height, int grid_size, int fixed_cell) {
  GalleryLayout l;
  const float n = static_cast<float>(std::max(1, grid_size));
  l.gap = kLayoutGap;
  l.toolbar = {kLayoutMargin, kLayoutMargin, width - 2 * kLayoutMargin, kToolbarHeight};
  l.messages = {kLayoutMargin, l.toolbar.y + kToolbarHeight, width - 2 * kLayoutMargin,
                kMessageHeight};
  const float top = l.messages.y + kMessageHeight;
  const float avail_h = std::max(64.0f, height - top - kLayoutMargin);
  const float side_min = std::max(kSidePanelMinWidth, kSidePanelShare * width);
  float grid;
  if (fixed_cell > 0) {
    l.cell = static_cast<float>(fixed_cell);
    grid = n * l.cell + (n - 1) * l.gap;
  } else {
    grid = std::min(width - 2 * kLayoutMargin - 2 * l.gap - side_min, avail_h);
    grid = std::max(grid, 32.0f * n + (n - 1) * l.gap);
    l.cell = std::floor((grid - (n - 1) * l.gap) / n);
    grid = n * l.cell + (n - 1) * l.gap;
  }
  l.grid = {kLayoutMargin, top, grid, grid};
  const float side_x = l.grid.x + grid + 2 * l.gap;
  l.side = {side_x, top, std::max(120.0f, width - side_x - kLayoutMargin), avail_h};
  return l;
}

std::pair<int, int> window_size_for_cells(int grid_size, int cell) {
  const float n = static_cast<float>(grid_size);
  const float grid = n * static_cast<float>(cell) + (n - 1) * kLayoutGap;
  const float w = 2 * kLayoutMargin + grid + 2 * kLayoutGap + 560.0f;
  const float h = kLayoutMargin + kToolbarHeight + kMessageHeight + grid + kLayoutMargin;
  return {static_cast<int>(std::ceil(w)), static_cast<int>(std::ceil(h))};
}

std::pair<int, int> fit_window_to(int width, int height, WorkArea area) {
  const auto fit = [](int size, int available, int smallest) {
    if (available <= 0 || size <= available) return size;
    return std::max(smallest, static_cast<int>(0.95 * available));
  };
  return {fit(width, area.w, 320), fit(height, area.h, 240)};
}

}  // namespace app
