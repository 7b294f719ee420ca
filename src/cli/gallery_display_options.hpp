// Options the window-opening commands (`gallery`, `bench-gui`) share: which model, which
// grid, and how the cells are rendered. One place, so they validate the same way.
#pragma once

#include "app/gallery_app.hpp"
#include "cli/arg_parser.hpp"

namespace cli {

// --space and the kind's own source option (--model for bodies, --image for photos) against
// the program's catalogue of kinds. `source` gets the source given, if one was. Throws
// ArgError naming the option.
const app::SpaceKind& read_space_kind(const ArgParser& args, std::optional<std::string>& source);

// Reads --space, --model, --image, --grid, --cell-size, --samples, --animation-samples and
// --animation-scale into `o`; `default_cell_size` 0 means "fit the window". Throws ArgError with
// the option name.
void read_gallery_display_options(const ArgParser& args, int default_cell_size,
                                  app::GalleryOptions& o);

}  // namespace cli
