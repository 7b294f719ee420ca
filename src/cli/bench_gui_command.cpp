// `bench-gui`: frame times of the viewer's grid during zoom animations (3x3 cells of 400x400
// px by default) and launch-to-first-grid time. Needs a display: run it under
// `xvfb-run -a -s "-screen 0 1900x1400x24"` on a machine without one.
#include <unistd.h>
#include <filesystem>
#include <iostream>
#include <string>

#include "app/gallery_app.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery bench-gui [--clicks N] [--cell-size PX] [--grid 3|5]\n"
    "                                    [--samples N] [--animation-samples N] [--model FILE]\n"
    "                                    [--animation-scale F] [--breakdown]\n"
    "Opens the viewer, clicks N cells automatically (default 12, i.e. 3 planes), and prints\n"
    "median / 95th percentile frame times of the zoom animations and the launch-to-first-grid\n"
    "time. Uses a throw-away session file. Example without a display:\n"
    "  xvfb-run -a -s \"-screen 0 1900x1400x24\" sequential-gallery bench-gui\n";

int run(int argc, char** argv) {
  const auto launch = std::chrono::steady_clock::now();
  cli::ArgParser args(argc, argv, {"help", "breakdown"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help", "breakdown", "clicks", "cell-size", "grid", "samples",
                       "animation-samples", "animation-scale", "model"});
  app::GalleryOptions o;
  o.launch_time = launch;
  if (const auto m = args.get("model")) o.model_path = *m;
  o.grid_size = args.get_int("grid", 3);
  if (o.grid_size != 3 && o.grid_size != 5) throw cli::ArgError("--grid must be 3 or 5");
  o.cell_size = args.get_int("cell-size", 400);
  if (o.cell_size < 32) throw cli::ArgError("--cell-size must be at least 32");
  o.samples = args.get_int("samples", 4);
  o.animation_samples = args.get_int("animation-samples", 0);
  o.animation_scale = static_cast<float>(args.get_double("animation-scale", 1.0));
  if (!(o.animation_scale >= 0.25f && o.animation_scale <= 1.0f)) {
    throw cli::ArgError("--animation-scale must be between 0.25 and 1");
  }
  o.benchmark_clicks = args.get_int("clicks", 12);
  o.benchmark_breakdown = args.has("breakdown");
  if (o.benchmark_clicks < 1) throw cli::ArgError("--clicks must be at least 1");
  const int grid_px = o.grid_size * o.cell_size + (o.grid_size - 1) * 6;
  o.window_width = grid_px + 16 + 548;
  o.window_height = grid_px + 50;
  o.resume = app::GalleryOptions::Resume::kNo;
  o.session_path = std::filesystem::temp_directory_path() /
                   ("sg-bench-gui-" + std::to_string(::getpid()) + ".json");
  const int rc = app::run_gallery(o);
  std::error_code ec;
  std::filesystem::remove(o.session_path, ec);
  return rc;
}

const cli::CommandRegistration reg{"bench-gui",
                                   "benchmark: viewer frame times during zoom animations", &run};

}  // namespace
