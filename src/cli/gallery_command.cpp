// `gallery` (the default command): the Sequential Gallery window.
#include <algorithm>
#include <iostream>
#include <string>

#include "app/gallery_app.hpp"
#include "app/session_store.hpp"
#include "bench/window_timing.hpp"
#include "body/measurement_solve.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/gallery_display_options.hpp"
#include "sps/plane_search.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery [gallery] [options]\n"
    "  --space body|photo      what to design: body shapes (default) or a photo's colours\n"
    "  --model MODEL           female, male, neutral (built in) or FILE.npz; default: the\n"
    "                          model last started in the window's New-search panel, at first\n"
    "                          neutral\n"
    "  --image FILE            photo to enhance, PNG or JPEG (default: a built-in picture)\n"
    "  --components K          shape components explored (default 10; a model with fewer\n"
    "                          explores all it has, and says so)\n"
    "  --grid 3|5              grid size (default 3)\n"
    "  --clicks N              zoom clicks per plane (default 4)\n"
    "  --seed N                random seed of a new search (default 1)\n"
    "  --target NAME=VALUE     (bodies; repeatable) start at the nearest body meeting it, e.g.\n"
    "                          height=1.80 mass=85 (names: see `measure --help`)\n"
    "  --hold NAME[=VALUE]     (bodies; repeatable) keep that measurement in every cell (a bare\n"
    "                          name holds the current best's value); the window can toggle it\n"
    "  --session FILE          session autosave file (default\n"
    "                          $XDG_STATE_HOME/sequential-gallery/session.json)\n"
    "  --resume ask|yes|no     what to do with an existing session (default ask)\n"
    "  --save-path FILE        default file for \"Save\" (default: as last time, else\n"
    "                          body.glb / photo.png in the current folder)\n"
    "  --file-dialog auto|builtin  \"Save as...\": the desktop's dialog (zenity/kdialog) if\n"
    "                          installed, else the in-app browser (default auto)\n"
    "  --view front|side|three-quarter   (default: as last time)\n"
    "  --window WxH            window size (default: as last time, else 1600x1000)\n"
    "  --cell-size PX          grid cell size in pixels (default: fit the window)\n"
    "  --samples N             MSAA samples per cell (default 4, 0 = off)\n"
    "  --animation-samples N   N > 0 keeps MSAA while animating (default 0: off)\n"
    "  --animation-scale F     cell resolution factor while animating (default 1)\n"
    "  --zoom-seconds S        zoom animation length (default 1.5)\n"
    "  --screenshot FILE.png   F12 writes a screenshot of the window there\n"
    "  --screenshot-after-frames N   write it after N frames (with --quit-after-screenshot)\n"
    "  --report-layout         print each grid cell's window position and size and each\n"
    "                          message shown, as [layout] and [message] lines (for tests)\n"
    "  --optimizer-delay-ms MS (testing) hold each optimizer run back, to see the UI stay live\n"
    "  --benchmark-clicks N    click N cells automatically, print frame-time statistics of the\n"
    "                          zoom animations and launch-to-first-grid time, then exit\n";

int run(int argc, char** argv) {
  const auto launch = std::chrono::steady_clock::now();
  cli::ArgParser args(argc, argv, {"help", "quit-after-screenshot", "report-layout"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help",
                       "space",
                       "image",
                       "file-dialog",
                       "model",
                       "components",
                       "grid",
                       "clicks",
                       "seed",
                       "session",
                       "resume",
                       "save-path",
                       "view",
                       "window",
                       "cell-size",
                       "samples",
                       "animation-samples",
                       "animation-scale",
                       "zoom-seconds",
                       "screenshot",
                       "screenshot-after-frames",
                       "quit-after-screenshot",
                       "benchmark-clicks",
                       "report-layout",
                       "optimizer-delay-ms",
                       "target",
                       "hold"});
  app::GalleryOptions o;
  o.launch_time = launch;
  cli::read_gallery_display_options(args, 0, o);
  o.components = args.get_int("components", 0);
  o.targets = args.get_all("target");
  o.holds = args.get_all("hold");
  if (!o.targets.empty() && !o.holds.empty()) {
    // A target on a held measurement must agree with the hold: refused here rather than
    // solved and then held at another value.
    try {
      std::vector<body::MeasurementTarget> targets, holds;
      for (const auto& t : o.targets) targets.push_back(body::parse_target(t, true));
      for (const auto& h : o.holds) holds.push_back(body::parse_target(h, false));
      (void)body::targets_with_holds(std::move(targets), holds);
    } catch (const std::invalid_argument& e) {
      throw cli::ArgError(std::string("--target/--hold: ") + e.what());
    }
  }
  o.zoom_levels = args.get_int("clicks", 4);
  if (o.zoom_levels < 1 || o.zoom_levels > 8) throw cli::ArgError("--clicks must be 1..8");
  if (args.has("components") && (o.components < 1 || o.components > sps::kMaxSearchDims)) {
    throw cli::ArgError("--components must be 1.." + std::to_string(sps::kMaxSearchDims) +
                        " (more is not searchable by clicking)");
  }
  o.seed = static_cast<std::uint64_t>(args.get_int("seed", 1));
  o.session_path = args.get_or("session", app::default_session_path().string());
  const std::string resume = args.get_or("resume", "ask");
  if (resume == "ask") {
    o.resume = app::ResumePolicy::kAsk;
  } else if (resume == "yes") {
    o.resume = app::ResumePolicy::kYes;
  } else if (resume == "no") {
    o.resume = app::ResumePolicy::kNo;
  } else {
    throw cli::ArgError("--resume must be ask, yes or no");
  }
  o.save_path = args.get_or("save-path", "");
  o.file_dialog = args.get_or("file-dialog", "auto");
  if (o.file_dialog != "auto" && o.file_dialog != "builtin") {
    throw cli::ArgError("--file-dialog must be auto or builtin");
  }
  if (const auto v = args.get("view")) {
    const auto preset = render::parse_view_preset(*v);
    if (!preset) throw cli::ArgError("--view must be front, side or three-quarter");
    o.view = *preset;
  }
  if (const auto w = args.get("window")) {
    char x = 0;
    if (std::sscanf(w->c_str(), "%d%c%d", &o.window_width, &x, &o.window_height) != 3 ||
        o.window_width < 320 || o.window_height < 240) {
      throw cli::ArgError("--window must look like 1600x1000");
    }
  }
  o.zoom_seconds = args.get_double("zoom-seconds", 1.5);
  if (!(o.zoom_seconds > 0.0)) throw cli::ArgError("--zoom-seconds must be positive");
  o.screenshot_path = args.get_or("screenshot", "");
  o.screenshot_after_frames = args.get_int("screenshot-after-frames", -1);
  o.quit_after_screenshot = args.has("quit-after-screenshot");
  if (const int clicks = args.get_int("benchmark-clicks", 0); clicks > 0) {
    bench::WindowTimingOptions timing;
    timing.clicks = clicks;
    o.observer = std::make_shared<bench::WindowTiming>(timing);
  }
  o.report_layout = args.has("report-layout");
  o.optimizer_delay_ms = std::max(0, args.get_int("optimizer-delay-ms", 0));
  if (o.observer && !args.has("resume")) o.resume = app::ResumePolicy::kNo;
  return app::run_gallery(o);
}

const cli::CommandRegistration reg{"gallery", "the Sequential Gallery window (default command)",
                                   &run};

}  // namespace
