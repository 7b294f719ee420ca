// `bench-gui`: frame times of the viewer's grid during zoom animations (3x3 cells of 400x400
// px by default) and launch-to-first-grid time. Needs a display: run it under
// `xvfb-run -a -s "-screen 0 1900x1400x24"` on a machine without one.
#include <unistd.h>
#include <filesystem>
#include <iostream>
#include <string>

#include "app/gallery_app.hpp"
#include "app/gallery_layout.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/gallery_display_options.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery bench-gui [--clicks N] [--cell-size PX] [--grid 3|5]\n"
    "                                    [--samples N] [--animation-samples N] [--model "
    "female|male|neutral|FILE]\n"
    "                                    [--animation-scale F] [--breakdown]\n"
    "                                    [--space body|photo] [--image FILE]\n"
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
                       "animation-samples", "animation-scale", "model", "space", "image"});
  app::GalleryOptions o;
  o.launch_time = launch;
  cli::read_gallery_display_options(args, 400, o);
  o.benchmark_clicks = args.get_int("clicks", 12);
  o.benchmark_breakdown = args.has("breakdown");
  if (o.benchmark_clicks < 1) throw cli::ArgError("--clicks must be at least 1");
  const int n = o.grid_size > 0 ? o.grid_size : o.catalogue->get(o.space).grid_size;
  const auto [w, h] = app::window_size_for_cells(n, o.cell_size);
  o.window_width = w;
  o.window_height = h;
  o.remember_ui = false;
  o.resume = app::ResumePolicy::kNo;
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
