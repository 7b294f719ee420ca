// What bench-gui measures of the window, watching its frame loop (app::FrameObserver): frame
// times of the zoom animations after clicks it makes itself, frames while the camera orbits
// (it turns every frame, so every cell is drawn again each frame), the time from a click to
// the end of the frame that shows it, the launch-to-first-grid time and the process's peak
// memory when the first grid is shown. Plain timing, no GL.
#pragma once

#include <vector>

#include "app/frame_observer.hpp"

namespace bench {

struct WindowTimingOptions {
  int clicks = 12;         // cells clicked (bench::kClickPattern in turn), one per settled grid
  int orbit_frames = 0;    // before the clicks: frames with the camera turning
  bool breakdown = false;  // also time the phases of each frame (adds glFinish)
};

class WindowTiming final : public app::FrameObserver {
 public:
  explicit WindowTiming(WindowTimingOptions options) : options_(options) {}

  Request frame_started(const FrameStart& frame) override;
  bool wants_breakdown() const override { return options_.breakdown; }
  void phases(double prepare_ms, double cells_ms) override;
  void presented_phases(double present_ms, double swap_ms) override;
  bool waits_for_presented() const override { return click_pending_; }
  void frame_presented(Clock::time_point at) override;
  void first_grid(double launch_seconds) override;
  void report(const app::WindowFacts& facts) const override;

  // Each timed click's milliseconds, and those of clicks that zoomed in and that ended the
  // plane (sorted at the frame after the click; the last click's kind may still be pending).
  const std::vector<double>& click_ms() const { return click_ms_; }
  const std::vector<double>& zoom_click_ms() const { return zoom_click_ms_; }
  const std::vector<double>& ending_click_ms() const { return ending_click_ms_; }

  // The process's peak resident set so far, in MiB.
  static double peak_rss_mb();

 private:
  bool orbit_done() const { return orbited_ >= options_.orbit_frames && !orbit_this_frame_; }

  WindowTimingOptions options_;
  // Orbiting.
  int orbited_ = 0;
  int settled_frames_ = 0;
  bool first_grid_ = false;
  bool orbit_this_frame_ = false;
  bool previous_orbit_ = false;
  // Clicks and the zoom animations they start.
  int clicks_done_ = 0;
  bool click_pending_ = false;
  Clock::time_point click_at_{};
  Clock::time_point previous_start_{};
  double launch_seconds_ = 0.0;
  double startup_rss_mb_ = 0.0;
  std::vector<double> orbit_ms_;
  std::vector<double> click_ms_;
  bool click_to_sort_ = false;  // the last click's kind is known at the next frame's start
  std::vector<double> zoom_click_ms_, ending_click_ms_;
  std::vector<double> animation_ms_;
  std::vector<double> prepare_ms_, cells_ms_, present_ms_, swap_ms_;
};

// The value below which a fraction p of `v` lies (linear between ranks); 0 for none.
double percentile_of(std::vector<double> v, double p);

}  // namespace bench
