// Where the gallery's panels go, as pure arithmetic on the window size: the window (view and
// cell rendering) and bench-gui (window size for a given cell size) share this one source.
#pragma once

#include <utility>

namespace app {

struct LayoutRect {
  float x = 0, y = 0, w = 0, h = 0;
};

// The grid takes the window's whole height at the left; the toolbar and the message line head
// the side column. (Above the grid they took 56 of the default window's 720 px, and the cells
// were 210 px high instead of 230: a person tells bodies apart by a couple of pixels.)
struct GalleryLayout {
  LayoutRect toolbar;   // buttons, view toggles, plane / click count (wraps onto rows)
  LayoutRect messages;  // the message lines: always visible, never below the fold
  LayoutRect grid;      // square
  LayoutRect side;      // previews, inspector, history, save, open (scrolls if short)
  float cell = 0;       // cell edge, logical pixels
  float gap = 0;
  int toolbar_rows = 1;
};

constexpr float kLayoutMargin = 8.0f;
constexpr float kLayoutGap = 6.0f;
constexpr float kToolbarRowHeight = 26.0f;
// The toolbar's items side by side at the default font (buttons, view toggles, plane and
// click count, source name); a narrower side column wraps them onto more rows.
constexpr float kToolbarOneRowWidth = 1040.0f;
constexpr float kMessageHeight = 40.0f;       // two lines of text, wrapped
constexpr float kSidePanelMinWidth = 360.0f;  // below this the previews get too small
constexpr float kSidePanelShare = 0.28f;      // of the window width at most, so the grid rules

// `fixed_cell` > 0 fixes the cell edge (bench-gui, tests); 0 fits the grid to the window.
// `toolbar_rows` > 0: the rows the toolbar really took (the view counts them as it wraps; at
// most 6); 0: toolbar_rows_for() estimates them from the column's width.
GalleryLayout compute_layout(float width, float height, int grid_size, int fixed_cell = 0,
                             int toolbar_rows = 0);

// How many rows the toolbar takes in a side column `width` wide (1-3).
int toolbar_rows_for(float width);

// The window size that shows n x n cells of `cell` pixels beside the side panel.
std::pair<int, int> window_size_for_cells(int grid_size, int cell);

// A screen's usable area (without panels and docks), in screen pixels; w or h 0 = unknown.
struct WorkArea {
  int w = 0, h = 0;
};

// The window size that fits `area`: a size that does not fit is shrunk to 95% of the area
// (room for the title bar and borders), never below the smallest window (320x240); an unknown
// area leaves the size as it is.
std::pair<int, int> fit_window_to(int width, int height, WorkArea area);

}  // namespace app
