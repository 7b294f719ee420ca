// `bench-gui`: frame times of the viewer's grid during zoom animations (3x3 cells of 400x400
// px by default) and launch-to-first-grid time. Needs a display: run it under
// `xvfb-run -a -s "-screen 0 1900x1400x24"` on a machine without one.
#include <unistd.h>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/gallery_app.hpp"
#include "app/gallery_layout.hpp"
#include "bench/long_session.hpp"
#include "bench/window_timing.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/gallery_display_options.hpp"
#include "spaces/space_factory.hpp"
#include "util/atomic_file.hpp"
#include "util/file_lock.hpp"
#include "util/file_read.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery bench-gui [--clicks N] [--cell-size PX] [--grid 3|5]\n"
    "                                    [--samples N] [--animation-samples N] [--model "
    "female|male|neutral|FILE]\n"
    "                                    [--animation-scale F] [--breakdown]\n"
    "                                    [--space body|photo] [--image FILE]\n"
    "                                    [--orbit-frames N] [--planes-done N]\n"
    "                                    [--session FILE] [--write-session FILE]\n"
    "Opens the viewer, turns the camera for N frames (--orbit-frames, default 90), clicks N\n"
    "cells automatically (default 12, i.e. 3 planes), and prints median / 95th percentile frame\n"
    "times of the orbit and of the zoom animations, the click-to-frame time, the\n"
    "launch-to-first-grid time and the peak memory at the first grid. Uses a throw-away\n"
    "session file: a fresh one, a copy of --session FILE (resumed), or with --planes-done N\n"
    "one made first by clicking through N planes in-process (then the window starts in a new\n"
    "process, so its start-up time and memory are the window's alone). --write-session FILE\n"
    "--planes-done N only writes that session (no window). Example without a display:\n"
    "  xvfb-run -a -s \"-screen 0 1900x1400x24\" sequential-gallery bench-gui\n";

namespace fs = std::filesystem;

fs::path temporary_session(const std::string& what) {
  return fs::temp_directory_path() /
         ("sg-bench-gui-" + what + "-" + std::to_string(::getpid()) + ".json");
}

// Starts this program again as `bench-gui <args> --session FILE --delete-session`: the window
// then starts in a process that never held the session being made.
[[noreturn]] void run_again_on(int argc, char** argv, const fs::path& session) {
  std::vector<std::string> args{"sequential-gallery", "bench-gui"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--planes-done") {
      ++i;  // and its value
      continue;
    }
    if (a.rfind("--planes-done=", 0) == 0) continue;
    args.push_back(a);
  }
  args.insert(args.end(), {"--session", session.string(), "--delete-session"});
  std::vector<char*> raw;
  for (auto& a : args) raw.push_back(a.data());
  raw.push_back(nullptr);
  std::cout.flush();
  ::execv("/proc/self/exe", raw.data());
  std::error_code ec;
  fs::remove(session, ec);
  throw std::runtime_error("bench-gui: cannot start the window process again");
}

int run(int argc, char** argv) {
  const auto launch = std::chrono::steady_clock::now();
  cli::ArgParser args(argc, argv, {"help", "breakdown", "delete-session"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help", "breakdown", "clicks", "cell-size", "grid", "samples",
                       "animation-samples", "animation-scale", "model", "space", "image",
                       "orbit-frames", "planes-done", "session", "write-session",
                       "delete-session"});
  app::GalleryOptions o;
  o.launch_time = launch;
  cli::read_gallery_display_options(args, 400, o);
  bench::WindowTimingOptions timing;
  timing.clicks = args.get_int("clicks", 12);
  timing.breakdown = args.has("breakdown");
  if (timing.clicks < 1) throw cli::ArgError("--clicks must be at least 1");
  timing.orbit_frames = args.get_int("orbit-frames", 90);
  if (timing.orbit_frames < 0) throw cli::ArgError("--orbit-frames must be at least 0");
  o.observer = std::make_shared<bench::WindowTiming>(timing);
  const int planes_done = args.get_int("planes-done", 0);
  if (planes_done < 0) throw cli::ArgError("--planes-done must be at least 0");
  if (planes_done > 0 && args.has("session")) {
    throw cli::ArgError("--planes-done makes a session; --session uses one: give one of them");
  }
  if (args.has("write-session") && planes_done == 0) {
    throw cli::ArgError("--write-session needs --planes-done N");
  }
  if (planes_done > 0) {
    const fs::path file = args.has("write-session") ? fs::path(args.require("write-session"))
                                                    : temporary_session("long");
    const int made = bench::write_long_session(app::controller_options(o), &spaces::open_space,
                                               planes_done, file);
    std::cout << "session: " << made << " finished planes made in-process, " << fs::file_size(file)
              << " bytes" << std::endl;
    if (args.has("write-session")) return 0;
    run_again_on(argc, argv, file);
  }
  const int n = o.grid_size > 0 ? o.grid_size : o.catalogue->get(o.space).grid_size;
  const auto [w, h] = app::window_size_for_cells(n, o.cell_size);
  o.window_width = w;
  o.window_height = h;
  o.remember_ui = false;
  o.resume = app::ResumePolicy::kNo;
  o.session_path = temporary_session("run");
  std::error_code ec;
  if (args.has("session")) {
    // A copy: the benchmark's clicks never change the file given.
    const fs::path given = args.require("session");
    util::write_file_atomically(o.session_path, util::read_regular_file(given, 256u << 20));
    if (args.has("delete-session")) fs::remove(given, ec);
    o.resume = app::ResumePolicy::kYes;
  }
  const int rc = app::run_gallery(o);
  fs::remove(o.session_path, ec);
  fs::remove(util::lock_path_for(o.session_path), ec);
  return rc;
}

const cli::CommandRegistration reg{"bench-gui",
                                   "benchmark: viewer frame times during zoom animations", &run};

}  // namespace
