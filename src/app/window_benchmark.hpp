// What bench-gui measures besides the zoom animations: frames while the camera orbits (it
// turns every frame, so every cell is drawn again each frame), the time from a click to the
// end of the frame that shows it, and the process's peak memory when the first grid is shown.
// Plain timing, no GL: the window loop reports its frames here.
#pragma once

#include <chrono>
#include <vector>

namespace app {

class WindowBenchmark {
 public:
  using Clock = std::chrono::steady_clock;

  // `orbit_frames` frames of orbiting once the window has settled (0: none).
  explicit WindowBenchmark(int orbit_frames = 0) : orbit_frames_(orbit_frames) {}

  // The first grid is on screen: the peak memory so far is the start-up memory.
  void first_grid();
  // At the start of each frame: whether the camera turns in it. `settled`: nothing animates
  // and no optimizer runs. Orbiting starts once the window has drawn a few settled frames
  // after the first grid (a resumed session's history thumbnails are drawn by then).
  bool frame_started(Clock::time_point start, bool settled);
  // The orbit frames are all done (the clicks may start).
  bool orbit_done() const { return orbited_ >= orbit_frames_ && !orbit_this_frame_; }
  // A click was queued for this frame; frame_presented() ends its click-to-frame time.
  void click_queued(Clock::time_point when);
  bool click_pending() const { return click_pending_; }
  void frame_presented(Clock::time_point when);

  // Prints the orbit frame times, the click-to-frame times and the peak memory.
  void report() const;

  // The process's peak resident set so far, in MiB.
  static double peak_rss_mb();

 private:
  int orbit_frames_ = 0;
  int orbited_ = 0;
  int settled_frames_ = 0;
  bool first_grid_ = false;
  bool orbit_this_frame_ = false;
  bool previous_orbit_ = false;
  Clock::time_point previous_start_{};
  bool click_pending_ = false;
  Clock::time_point click_at_{};
  double startup_rss_mb_ = 0.0;
  std::vector<double> orbit_ms_;
  std::vector<double> click_ms_;
};

// The value below which a fraction p of `v` lies (linear between ranks); 0 for none.
double percentile_of(std::vector<double> v, double p);

}  // namespace app
