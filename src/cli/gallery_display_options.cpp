#include "cli/gallery_display_options.hpp"

#include "spaces/space_factory.hpp"

namespace cli {

void read_gallery_display_options(const ArgParser& args, int default_cell_size,
                                  app::GalleryOptions& o) {
  const app::SpaceCatalogue& kinds = spaces::catalogue();
  o.catalogue = &kinds;
  o.space_given = args.get("space").has_value();
  const app::SpaceKind* kind = &kinds.default_kind();
  if (o.space_given) {
    kind = kinds.find(*args.get("space"));
    if (kind == nullptr) throw ArgError("--space must be " + kinds.names(" or "));
  }
  o.space = kind->name;
  // Each kind names its own source option (--model for bodies, --image for photos).
  for (const app::SpaceKind& k : kinds.kinds()) {
    const auto source = args.get(k.source_option);
    if (!source) continue;
    if (&k != kind) {
      throw ArgError("--" + k.source_option + " is for --space " + k.name + "; a " + kind->name +
                     " search takes --" + kind->source_option);
    }
    o.source = *source;
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
