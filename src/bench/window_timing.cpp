#include "bench/window_timing.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bench/long_session.hpp"

namespace bench {

namespace {

// Frames drawn at rest after the first grid before the camera starts to turn: the settled
// grid's antialiased redraw and a long session's history thumbnails (four a frame) are
// done by then, so the orbit frames measure orbiting alone.
constexpr int kSettleFrames = 30;

double ms_between(app::FrameObserver::Clock::time_point a,
                  app::FrameObserver::Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

double percentile_of(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

double WindowTiming::peak_rss_mb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void WindowTiming::first_grid(double launch_seconds) {
  if (first_grid_) return;
  first_grid_ = true;
  launch_seconds_ = launch_seconds;
  startup_rss_mb_ = peak_rss_mb();
}

app::FrameObserver::Request WindowTiming::frame_started(const FrameStart& frame) {
  // The last click's frame zoomed in, or the click ended the plane (the optimizer's turn, the
  // next plane's grid): two kinds of work, timed apart so that sessions whose planes end
  // after fewer clicks are compared like with like.
  if (click_to_sort_) {
    click_to_sort_ = false;
    (frame.previous_frame_submitted ? ending_click_ms_ : zoom_click_ms_)
        .push_back(click_ms_.back());
  }
  if (frame.previous_frame_zoomed) animation_ms_.push_back(ms_between(previous_start_, frame.at));
  if (previous_orbit_) orbit_ms_.push_back(ms_between(previous_start_, frame.at));
  previous_start_ = frame.at;
  Request request;
  orbit_this_frame_ = false;
  if (first_grid_ && orbited_ < options_.orbit_frames) {
    if (settled_frames_ < kSettleFrames) {
      settled_frames_ = frame.settled ? settled_frames_ + 1 : 0;
    } else {
      orbit_this_frame_ = true;
      ++orbited_;
    }
  }
  previous_orbit_ = orbit_this_frame_;
  request.orbit = orbit_this_frame_;
  // One click per settled grid, after the orbit frames.
  if (!frame.first_grid_shown || !frame.settled || !orbit_done()) return request;
  if (clicks_done_ >= options_.clicks) {
    request.quit = true;
    return request;
  }
  const auto& p = kClickPattern[clicks_done_ % 8];
  request.click = std::make_pair(p[0], p[1]);
  click_pending_ = true;
  click_at_ = frame.at;
  ++clicks_done_;
  return request;
}

void WindowTiming::phases(double prepare_ms, double cells_ms) {
  prepare_ms_.push_back(prepare_ms);
  cells_ms_.push_back(cells_ms);
}

void WindowTiming::presented_phases(double present_ms, double swap_ms) {
  present_ms_.push_back(present_ms);
  swap_ms_.push_back(swap_ms);
}

void WindowTiming::frame_presented(Clock::time_point at) {
  if (!click_pending_) return;
  click_pending_ = false;
  click_ms_.push_back(ms_between(click_at_, at));
  click_to_sort_ = true;
}

void WindowTiming::report(const app::WindowFacts& f) const {
  std::printf("renderer: %s\n", f.renderer.c_str());
  std::printf("space: %s\n", f.space.c_str());
  std::printf(
      "grid: %dx%d cells of %dx%d px, MSAA %d samples at rest; while animating %s at %.2f "
      "resolution; window %dx%d\n",
      f.grid_size, f.grid_size, f.cell_pixels, f.cell_pixels, f.samples,
      f.animation_multisample ? "MSAA" : "no MSAA", static_cast<double>(f.animation_scale),
      f.framebuffer_w, f.framebuffer_h);
  std::printf("launch to first grid: %.0f ms\n", launch_seconds_ * 1000.0);
  std::printf("zoom animation frames: %zu over %d clicks\n", animation_ms_.size(), clicks_done_);
  const double worst =
      animation_ms_.empty() ? 0.0 : *std::max_element(animation_ms_.begin(), animation_ms_.end());
  std::printf("frame time median: %.1f ms  p95: %.1f ms  max: %.1f ms\n",
              percentile_of(animation_ms_, 0.5), percentile_of(animation_ms_, 0.95), worst);
  if (options_.breakdown) {
    std::printf(
        "  medians: cell preparation + upload %.1f ms, UI + cells rendered %.1f ms, "
        "window drawn + swapped %.1f ms (swap %.1f ms)\n",
        percentile_of(prepare_ms_, 0.5), percentile_of(cells_ms_, 0.5),
        percentile_of(present_ms_, 0.5), percentile_of(swap_ms_, 0.5));
  } else {
    std::printf("  (--breakdown times the phases of a frame; it adds glFinish calls)\n");
  }
  std::printf("last optimizer submit: %.2f s (worker thread)\n", f.last_submit_seconds);
  std::printf("session: %d finished planes at the end\n", f.planes_done);
  std::printf("start-up memory: peak RSS %.1f MB at the first grid (%.1f MB at the end)\n",
              startup_rss_mb_, peak_rss_mb());
  if (options_.orbit_frames > 0) {
    std::printf("orbit frames: %zu, frame time median: %.1f ms  p95: %.1f ms\n", orbit_ms_.size(),
                percentile_of(orbit_ms_, 0.5), percentile_of(orbit_ms_, 0.95));
  }
  if (!click_ms_.empty()) {
    std::printf("click to frame: %zu clicks, median: %.1f ms  p95: %.1f ms  max: %.1f ms\n",
                click_ms_.size(), percentile_of(click_ms_, 0.5), percentile_of(click_ms_, 0.95),
                *std::max_element(click_ms_.begin(), click_ms_.end()));
    std::printf("  zoom clicks: %zu, median: %.1f ms; plane-ending clicks: %zu, median: %.1f ms\n",
                zoom_click_ms_.size(), percentile_of(zoom_click_ms_, 0.5), ending_click_ms_.size(),
                percentile_of(ending_click_ms_, 0.5));
  }
  std::fflush(stdout);
}

}  // namespace bench
