// What a person can see of a body grid cell: the body cells' camera shows a frame of a fixed
// height at the body, so a cell of N pixels shows frame / N millimetres per pixel, and two
// bodies whose outlines differ by less than a couple of pixels look alike. The window takes
// its look-alike threshold from the cell size it really shows, and the body benchmark's
// pixel person (`simulate --function body --jnd-px D --cell-px N`) uses the same rule.
#pragma once

namespace app {

// Height (m) of what a body cell shows at the body: render::Camera's defaults, 4 m away with
// a 30 degree vertical field of view, 2 * 4 * tan(15 degrees) (render_tests check the match).
constexpr double kCellFrameHeightM = 2.0 * 4.0 * 0.26794919243112270;

// A body cell's height at the default 1280x720 window (`gallery --report-layout`).
constexpr int kDefaultCellPx = 210;

// The difference, in pixels, under which a person takes two cells for the same body.
constexpr double kDefaultJndPx = 2.0;

// Millimetres of body per pixel in a cell `cell_px` high (NaN-free: cell_px is clamped to 1).
double millimetres_per_pixel(double cell_px);

// The largest vertex distance (mm) two bodies must differ by to look different in a cell of
// `cell_px` pixels to a person who resolves `jnd_px` pixels: an outline moves by about a
// vertex's displacement across the view.
double look_alike_mm(double cell_px, double jnd_px = kDefaultJndPx);

// zoom_policy_for_cells(), the same rule as a session's ZoomPolicy, is in app/session.hpp.

}  // namespace app
