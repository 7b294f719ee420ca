#include "cli/gallery_display_options.hpp"

namespace cli {

void read_gallery_display_options(const ArgParser& args, int default_cell_size,
                                  app::GalleryOptions& o) {
  o.space = args.get_or("space", "body");
  o.space_given = args.get("space").has_value();
  if (o.space != "body" && o.space != "photo") throw ArgError("--space must be body or photo");
  if (const auto m = args.get("model")) {
    if (o.space != "body") throw ArgError("--model is for --space body; photos take --image");
    o.source = *m;
  }
  if (const auto m = args.get("image")) {
    if (o.space != "photo") throw ArgError("--image is for --space photo");
    o.source = *m;
  }
  o.grid_size = args.get_int("grid", 0);
  if (args.has("grid") && o.grid_size != 3 && o.grid_size != 5) {
    throw ArgError("--grid must be 3 or 5");
  }
  o.cell_size = args.get_int("cell-size", default_cell_size);
  if (o.cell_size != 0 && o.cell_size < 32) {
    throw ArgError("--cell-size must be at least 32 pixels");
  }
  o.samples = args.get_int("samples", 4);
  o.animation_samples = args.get_int("animation-samples", 0);
  if (o.samples < 0 || o.animation_samples < 0) {
    throw ArgError("--samples and --animation-samples must not be negative");
  }
  o.animation_scale = static_cast<float>(args.get_double("animation-scale", 1.0));
  if (!(o.animation_scale >= 0.25f && o.animation_scale <= 1.0f)) {
    throw ArgError("--animation-scale must be between 0.25 and 1");
  }
}

}  // namespace cli
