// The grid: the cells as images, their labels, the hovered cell's highlight and what differs
// in it from the current best, clicks (a zoom step each) and drags (orbiting every body).
#pragma once

#include <memory>
#include <vector>

#include "app/cell_view.hpp"
#include "app/panel_context.hpp"
#include "render/camera.hpp"

namespace app {

class GridPanel {
 public:
  // Draws the grid at `layout`; a drag orbits `camera` (returns true when it moved).
  bool draw(PanelContext& ctx, const GalleryLayout& layout, const std::vector<CellView>& cells,
            const PreparedCell* best, render::Camera& camera, long frame, bool report_layout);
  int hovered() const { return hovered_; }
  // The hovered cell's prepared point with its details (measurements), while one is hovered.
  const PreparedCell* hovered_details() const { return hovered_ >= 0 ? details_.get() : nullptr; }
  bool dragging() const { return dragging_; }
  void reset() { details_.reset(); }

 private:
  // The hovered cell against the current best: a one-line summary inside the cell (it covers
  // no neighbour); the full table while Shift is held, opening towards the grid's centre.
  void draw_hover_details(PanelContext& ctx, const LayoutRect& cell, const PreparedCell& best,
                          float centre_x, float centre_y);

  int hovered_ = -1;
  std::shared_ptr<const PreparedCell> details_;
  bool second_of_double_ = false;  // the press being released is a double-click's second
  bool dragging_ = false;
};

// Label of cell `index` on an n x n grid: 1-9 on 3x3, A-Y on 5x5 (also its key).
std::string cell_label(int index, int n);

}  // namespace app
