#include "app/gallery_layout.hpp"

#include <algorithm>
#include <cmath>

namespace app {

int toolbar_rows_for(float width) {
  if (width >= kToolbarOneRowWidth) return 1;
  return width >= kToolbarOneRowWidth / 2 ? 2 : 3;
}

GalleryLayout compute_layout(float width, float height, int grid_size, int fixed_cell,
                             int toolbar_rows) {
  GalleryLayout l;
  const float n = static_cast<float>(std::max(1, grid_size));
  l.gap = kLayoutGap;
  const float top = kLayoutMargin;
  const float avail_h = std::max(64.0f, height - 2 * kLayoutMargin);
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
  const float side_w = std::max(120.0f, width - side_x - kLayoutMargin);
  l.toolbar_rows = toolbar_rows > 0 ? std::min(toolbar_rows, 6) : toolbar_rows_for(side_w);
  l.toolbar = {side_x, top, side_w, kToolbarRowHeight * static_cast<float>(l.toolbar_rows)};
  l.messages = {side_x, l.toolbar.y + l.toolbar.h, side_w, kMessageHeight};
  const float side_top = l.messages.y + kMessageHeight;
  l.side = {side_x, side_top, side_w, std::max(64.0f, height - kLayoutMargin - side_top)};
  return l;
}

std::pair<int, int> window_size_for_cells(int grid_size, int cell) {
  const float n = static_cast<float>(grid_size);
  const float grid = n * static_cast<float>(cell) + (n - 1) * kLayoutGap;
  const float w = 2 * kLayoutMargin + grid + 2 * kLayoutGap + 560.0f;
  // The side column under the toolbar needs room for the previews and a tab even beside a
  // grid of small cells.
  const float h = std::max(2 * kLayoutMargin + grid, 480.0f);
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
