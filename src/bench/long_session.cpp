#include "bench/long_session.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bench {

const int kClickPattern[8][2] = {{0, 0}, {2, 1}, {1, 2}, {2, 2}, {0, 1}, {1, 0}, {2, 0}, {0, 2}};

int write_long_session(app::ControllerOptions options, const app::SpaceOpener& opener, int planes,
                       const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  options.session_path = path;
  options.resume = app::ResumePolicy::kNo;
  options.zoom_seconds = 0.0;
  options.morph_seconds = 0.0;
  options.log = false;
  // Only the newest copy is written: a save after every click would cost a second per plane
  // on a long session.
  options.background_autosave = true;
  app::GalleryController c(std::move(options), opener, 0.0);
  const int n = c.session().settings().grid_size;
  double t = 0.0;
  int clicks = 0;
  // A plane takes at most zoom_levels clicks; the bound only stops a session that never
  // finishes a plane.
  const int max_clicks = (planes + 1) * 8 * 4;
  while (c.session().planes_done() < planes && clicks < max_clicks) {
    c.begin_frame(t);
    if (c.busy()) {
      c.wait_for_optimizer(t);
    } else {
      const auto& p = kClickPattern[clicks % 8];
      c.queue(app::intent::ClickCell{std::min(p[0], n - 1), std::min(p[1], n - 1)});
      ++clicks;
    }
    t += 1.0;
  }
  c.begin_frame(t);
  c.save_now();
  if (!c.autosave_problem().empty()) {
    throw std::runtime_error("cannot write the long session: " + c.autosave_problem());
  }
  return c.session().planes_done();
}

}  // namespace bench
