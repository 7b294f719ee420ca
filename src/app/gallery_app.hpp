// The Sequential Gallery window: GLFW + Dear ImGui around a GalleryController (state, intents)
// and a GalleryView (panels, cells). This file is the shell: the window, the frame loop in
// the order "apply intents, prepare and draw cells, build and draw the UI", input, screenshots
// and the bench-gui measurements.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app/frame_observer.hpp"
#include "app/gallery_controller.hpp"
#include "app/space_catalogue.hpp"
#include "app/ui_prefs.hpp"
#include "render/camera.hpp"

namespace app {

struct GalleryOptions {
  // The kinds of design space the window can search (the command line's catalogue); must be
  // set, and outlive the window.
  const SpaceCatalogue* catalogue = nullptr;
  std::string space;                  // design space kind; empty: the catalogue's default
  bool space_given = false;           // --space was on the command line
  std::optional<std::string> source;  // the kind's source (--model, --image); none: its default
  int components = 0;                 // dimensions explored; 0: the kind's default
  int grid_size = 0;                  // 0 = the kind's default
  int zoom_levels = 4;
  std::uint64_t seed = 1;
  std::filesystem::path session_path;  // autosave file
  ResumePolicy resume = ResumePolicy::kAsk;
  std::vector<std::string> targets;  // --target name=value: start at the nearest such body
  std::vector<std::string> holds;    // --hold name[=value]: held in every cell

  int window_width = 0;  // 0 = as last time (else 1600x1000)
  int window_height = 0;
  int cell_size = 0;             // cell edge in pixels; 0 = fit the window
  int samples = 4;               // MSAA samples per cell
  int animation_samples = 0;     // > 0: keep MSAA while the grid animates (costly on llvmpipe)
  float animation_scale = 1.0f;  // cell resolution factor while the grid animates
  double zoom_seconds = 1.5;
  std::optional<render::ViewPreset> view;  // none: as last time
  std::string save_path;                   // empty: as last time, else the space's default
  std::string file_dialog = "auto";        // auto | builtin
  bool remember_ui = true;                 // read and write ui.json beside the session

  std::filesystem::path screenshot_path;  // F12 writes it; see screenshot_after_frames
  int screenshot_after_frames = -1;       // >= 0: write the screenshot after that many frames
  bool quit_after_screenshot = false;
  // Print the grid cells' window rectangles and each message shown (scripted tests).
  bool report_layout = false;
  int optimizer_delay_ms = 0;  // testing: hold each submission back this long

  // A watcher of the frames (bench-gui, gallery --benchmark-clicks: src/bench): it may click
  // and orbit, and the window closes when it says so. With one, the window measures the model
  // it was given, remembers nothing and draws without waiting for events or the display.
  std::shared_ptr<FrameObserver> observer;
  std::chrono::steady_clock::time_point launch_time = std::chrono::steady_clock::now();
};

// The controller options a window with `options` starts with (also used by the tests).
ControllerOptions controller_options(const GalleryOptions& options);
// The same for a window that remembers `prefs`: a search given no source starts on the one
// its kind remembers (a body search: the model chosen last time in the New-search panel).
ControllerOptions controller_options(const GalleryOptions& options, const UiPrefs& prefs);

// Runs the window until it is closed; returns the process exit code.
int run_gallery(const GalleryOptions& options);

}  // namespace app
