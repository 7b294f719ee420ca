#include "app/window_benchmark.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace app {

namespace {

// Frames drawn at rest after the first grid before the camera starts to turn: the settled
// grid's antialiased redraw and a long session's history thumbnails (four a frame) are
// done by then, so the orbit frames measure orbiting alone.
constexpr int kSettleFrames = 30;

double ms_between(WindowBenchmark::Clock::time_point a, WindowBenchmark::Clock::time_point b) {
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

double WindowBenchmark::peak_rss_mb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void WindowBenchmark::first_grid() {
  if (first_grid_) return;
  first_grid_ = true;
  startup_rss_mb_ = peak_rss_mb();
}

bool WindowBenchmark::frame_started(Clock::time_point start, bool settled) {
  if (previous_orbit_) orbit_ms_.push_back(ms_between(previous_start_, start));
  previous_start_ = start;
  orbit_this_frame_ = false;
  if (first_grid_ && orbited_ < orbit_frames_) {
    if (settled_frames_ < kSettleFrames) {
      settled_frames_ = settled ? settled_frames_ + 1 : 0;
    } else {
      orbit_this_frame_ = true;
      ++orbited_;
    }
  }
  previous_orbit_ = orbit_this_frame_;
  return orbit_this_frame_;
}

void WindowBenchmark::click_queued(Clock::time_point when) {
  click_pending_ = true;
  click_at_ = when;
}

void WindowBenchmark::frame_presented(Clock::time_point when) {
  if (!click_pending_) return;
  click_pending_ = false;
  click_ms_.push_back(ms_between(click_at_, when));
}

void WindowBenchmark::report() const {
  std::printf("start-up memory: peak RSS %.1f MB at the first grid (%.1f MB at the end)\n",
              startup_rss_mb_, peak_rss_mb());
  if (orbit_frames_ > 0) {
    std::printf("orbit frames: %zu, frame time median: %.1f ms  p95: %.1f ms\n", orbit_ms_.size(),
                percentile_of(orbit_ms_, 0.5), percentile_of(orbit_ms_, 0.95));
  }
  if (!click_ms_.empty()) {
    std::printf("click to frame: %zu clicks, median: %.1f ms  p95: %.1f ms  max: %.1f ms\n",
                click_ms_.size(), percentile_of(click_ms_, 0.5), percentile_of(click_ms_, 0.95),
                *std::max_element(click_ms_.begin(), click_ms_.end()));
  }
  std::fflush(stdout);
}

}  // namespace app
