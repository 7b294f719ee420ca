// The Sequential Gallery window: GLFW + Dear ImGui, a grid of offscreen-rendered bodies that
// zooms around the clicked cell, the optimizer on a worker thread, previews, history, undo,
// glTF export and an autosaved session.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "render/camera.hpp"

namespace app {

struct GalleryOptions {
  std::optional<std::string> model_path;  // none: the embedded default (or resumed session's)
  int components = 10;
  int grid_size = 3;
  int zoom_levels = 4;
  std::uint64_t seed = 1;
  std::filesystem::path session_path;  // autosave file
  enum class Resume { kAsk, kYes, kNo } resume = Resume::kAsk;

  int window_width = 1600;
  int window_height = 1000;
  int cell_size = 0;             // cell edge in pixels; 0 = fit the window
  int samples = 4;               // MSAA samples per cell
  int animation_samples = 0;     // > 0: keep MSAA while the grid animates (costly on llvmpipe)
  float animation_scale = 1.0f;  // cell resolution factor while the grid animates
  double zoom_seconds = 1.5;
  render::ViewPreset view = render::ViewPreset::kFront;
  std::string save_path = "body.glb";

  std::filesystem::path screenshot_path;  // F12 writes it; see screenshot_after_frames
  int screenshot_after_frames = -1;       // >= 0: write the screenshot after that many frames
  bool quit_after_screenshot = false;
  bool report_layout = false;
  int optimizer_delay_ms = 0;  // testing: hold each submission back this long  // print the grid
                               // cells' window rectangles (for scripted tests)

  // Benchmark: click automatically through `benchmark_clicks` cells, measure frame times
  // during the zoom animations and the launch-to-first-grid time, print them and exit.
  int benchmark_clicks = 0;
  bool benchmark_breakdown = false;  // also time the phases of each frame (adds glFinish)
  std::chrono::steady_clock::time_point launch_time = std::chrono::steady_clock::now();
};

// Runs the window until it is closed; returns the process exit code.
int run_gallery(const GalleryOptions& options);

}  // namespace app
