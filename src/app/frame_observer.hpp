// What the window's frame loop tells a watcher of its frames (bench-gui's measurements), and
// what the watcher may ask of the next frame: a click, an orbit step, the end. The window
// knows nothing of what is measured; the watchers live in src/bench.
#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace app {

// What the window is, for a report.
struct WindowFacts {
  std::string renderer;  // GL_RENDERER
  std::string space;     // the design space's description
  int grid_size = 0;
  int cell_pixels = 0;
  int samples = 0;  // MSAA at rest
  bool animation_multisample = false;
  float animation_scale = 1.0f;
  int framebuffer_w = 0, framebuffer_h = 0;
  double last_submit_seconds = 0.0;
  int planes_done = 0;
};

class FrameObserver {
 public:
  using Clock = std::chrono::steady_clock;
  virtual ~FrameObserver() = default;

  struct FrameStart {
    Clock::time_point at;
    bool settled = false;  // nothing animates and no optimizer runs
    bool first_grid_shown = false;
    bool previous_frame_zoomed = false;  // the last frame drew a zoom animation step
    // The last frame's state changes handed a choice to the optimizer (a click ended the plane).
    bool previous_frame_submitted = false;
  };
  struct Request {
    bool orbit = false;                        // turn the shared camera a step in this frame
    std::optional<std::pair<int, int>> click;  // (column, row) to click in this frame
    bool quit = false;                         // the measurements are done: report and close
  };
  // At the start of every frame, before the controller applies its intents.
  virtual Request frame_started(const FrameStart& frame) = 0;
  // The phases of a zoom animation frame (with glFinish between them, see wants_breakdown):
  // cell preparation and upload, UI and cells rendered, window drawn and swapped, the swap.
  virtual bool wants_breakdown() const { return false; }
  virtual void phases(double /*prepare_ms*/, double /*cells_ms*/) {}
  virtual void presented_phases(double /*present_ms*/, double /*swap_ms*/) {}
  // The frame that shows a requested click is on screen (GL finished).
  virtual bool waits_for_presented() const = 0;
  virtual void frame_presented(Clock::time_point at) = 0;
  // The first grid is on screen, `launch_seconds` after the program started.
  virtual void first_grid(double launch_seconds) = 0;
  // On quit: print what was measured.
  virtual void report(const WindowFacts& facts) const = 0;
};

}  // namespace app
