// What a person can see of a body grid cell: the body cells' default camera shows a frame of a
// fixed height at the body, so a cell of N pixels shows frame / N millimetres per pixel, and
// two bodies whose outlines differ by less than a couple of pixels look alike. A grid is
// framed to its tallest body (cell_frame_scale), or in close-ups on the band of heights where
// its bodies differ (cell_frame_for_band; spaces/body_framing.hpp), which shows its
// differences 1/s larger; the body space's perceptual distance reports them as they look at
// the default frame, so one threshold per cell size holds for every grid. The window takes its
// look-alike threshold from the cell size it really shows, and the body benchmark's pixel person
// (`simulate --function body --jnd-px D --cell-px N`) uses the same rule and the same framing.
#pragma once

namespace app {

// Height (m) of what a body cell shows at the body: render::Camera's defaults, 4 m away with
// a 30 degree vertical field of view, 2 * 4 * tan(15 degrees) (render_tests check the match).
constexpr double kCellFrameHeightM = 2.0 * 4.0 * 0.26794919243112270;

// A body cell's height at the default 1280x720 window (`gallery --report-layout`; 210 px
// while the toolbar sat above the grid; gallery_tests hold it to app::compute_layout).
constexpr int kDefaultCellPx = 230;

// The difference, in pixels, under which a person takes two cells for the same body.
constexpr double kDefaultJndPx = 2.0;

// The highest point (m above the floor) the default body camera shows at the body: looking 6
// degrees down from 4 m at 0.98 m, the top of its 30 degree view is 9 degrees above level,
// 1.398 + 3.978 * tan(9 degrees) (render_tests check the match).
constexpr double kCellFrameTopM = 2.028;

// The lowest point (m, below the floor) the default body camera shows at the body: 21 degrees
// below level from the same eye, 1.398 - 3.978 * tan(21 degrees).
constexpr double kCellFrameBottomM = -0.1289;

// Room left above the tallest body of a grid framed to it (m).
constexpr double kCellHeadroomM = 0.05;

// How far a grid whose tallest body stands `tallest_m` high is framed in: the default camera
// scaled by s about the floor point under the body (render::Camera::scaled_about_floor) shows
// that body 1/s larger, with kCellHeadroomM above its head. In [0.5, 1]: a grid with a body
// over 1.98 m keeps the default framing; a height that is not a positive number gives 1.
double cell_frame_scale(double tallest_m);

// How a grid's cells are framed: the default camera scaled by `scale` about the point
// `pivot_m` above the floor under the body (render::Camera::scaled_about_height), everything
// 1/scale larger. {1, 0} is the default framing; a grid framed to its tallest body keeps the
// floor where it was (pivot 0).
struct GridFrame {
  double scale = 1.0;
  double pivot_m = 0.0;
};

// The frame that shows the heights [bottom_m, top_m] (m above the floor) over the cell's whole
// height, as the default frame shows [kCellFrameBottomM, kCellFrameTopM]; scale in [0.25, 1]
// (a band taller than the default frame gets the default). Not finite or empty: {1, 0}.
GridFrame cell_frame_for_band(double bottom_m, double top_m);

// Millimetres of body per pixel in a cell `cell_px` high (NaN-free: cell_px is clamped to 1).
double millimetres_per_pixel(double cell_px);

// The largest vertex distance (mm) two bodies must differ by to look different in a cell of
// `cell_px` pixels to a person who resolves `jnd_px` pixels: an outline moves by about a
// vertex's displacement across the view.
double look_alike_mm(double cell_px, double jnd_px = kDefaultJndPx);

// How noisy the choices of a person who resolves `jnd_px` in cells of `cell_px` pixels are, for
// the search's estimate of the body in mind (sps::SearchOptions::choice_temperature_mm, RMS
// mm): a third of the look-alike threshold, never below the 3 mm fitted to a person who
// tells apart 5 mm. On the pixel person at 210 px (6.8 mm; 100 people, seeds 3000-3099) the
// mean gap went from 16.2 to 15.3 mm at plane 10 and from 14.9 to 13.1 at plane 15 with it;
// at 400 px (3.6 mm) it is within the noise of 3 mm.
constexpr double kChoiceTemperatureMm = 3.0;
// The largest vertex distance of two bodies over their RMS vertex distance, about (the
// conversion between the window's look-alike threshold and a threshold in RMS mm).
constexpr double kLargestPerRmsDistance = 3.0;
double choice_temperature_for_cells(double cell_px, double jnd_px = kDefaultJndPx);

// The same for the body benchmark's person who cannot tell apart bodies within `jnd_rms_mm`
// (RMS, `simulate --jnd-mm`): that threshold itself, never below kChoiceTemperatureMm (the
// perfect chooser's). A third of the pixel person's threshold above is about the same, as the
// largest vertex distance of two bodies is about three times their RMS distance. Refitted on
// the window's planes with the choices' regions (60 people each on seeds 2000-2059 and
// 3000-3059, mean gap at plane 15): the 5 mm person 5.42 mm with 3 mm, 5.12 with 4 and 5; the
// 10 mm person (seeds 2000-2059) 11.39 mm at plane 10 with 3 mm, 10.27 with 6, 10.00 with 10.
double choice_temperature_for_jnd_mm(double jnd_rms_mm);

// zoom_policy_for_cells(), the same rule as a session's ZoomPolicy, is in app/session.hpp.

}  // namespace app
