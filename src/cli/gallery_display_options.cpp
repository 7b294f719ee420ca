#include "cli/gallery_display_options.hpp"

#include "spaces/space_factory.hpp"

namespace cli {

const app::SpaceKind& read_space_kind(const ArgParser& args, std::optional<std::string>& source) {
  const app::SpaceCatalogue& kinds = spaces::catalogue();
  const app::SpaceKind* kind = &kinds.default_kind();
  if (const auto name = args.get("space")) {
    kind = kinds.find(*name);
    if (kind == nullptr) throw ArgError("--space must be " + kinds.names(" or "));
  }
  // Each kind names its own source option.
  for (const app::SpaceKind& k : kinds.kinds()) {
    const auto given = args.get(k.source_option);
    if (!given) continue;
    if (&k != kind) {
      throw ArgError("--" + k.source_option + " is for --space " + k.name + "; a " + kind->name +
                     " search takes --" + kind->source_option);
    }
    source = *given;
  }
  return *kind;
}

void read_gallery_display_options(const ArgParser& args, int default_cell_size,
                                  app::GalleryOptions& o) {
  o.catalogue = &spaces::catalogue();
  o.space_given = args.get("space").has_value();
  o.space = read_space_kind(args, o.source).name;
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
