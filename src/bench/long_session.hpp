// A session with many finished planes, made by clicking through them in-process with the real
// controller (the design space's perceptual zoom, the optimizer, autosave), for benchmarks of
// the window on a long session (bench-gui --planes-done N).
#pragma once

#include <filesystem>

#include "app/gallery_controller.hpp"

namespace bench {

// The cells bench-gui clicks, in turn (column, row on a 3x3 grid; a smaller grid clamps them).
extern const int kClickPattern[8][2];

}  // namespace bench

namespace bench {

// Clicks through planes of `options`' space (a fixed pattern of cells) until `planes` are
// finished, and saves the session to `path` (replacing a file there). `options`' session
// path, resume policy and animation times are set here. Returns the planes finished (planes
// that end early count as one each, like any other). Throws when the session cannot be saved.
int write_long_session(app::ControllerOptions options, const app::SpaceOpener& opener, int planes,
                       const std::filesystem::path& path);

}  // namespace bench
