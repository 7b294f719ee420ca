#include "spaces/space_factory.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "body/model_loader.hpp"
#include "spaces/body_space.hpp"
#include "spaces/photo_space.hpp"
#include "spaces/source_panels.hpp"

namespace spaces {

namespace {

app::SpaceKind body_kind() {
  app::SpaceKind k;
  k.name = "body";
  k.label = "body shape";
  k.source_noun = "Model";
  k.source_option = "model";
  k.dimensions = 10;
  k.grid_size = 3;
  k.file_extensions = {".npz", ".pkl"};
  k.open = [](const app::SpaceSettings& s) { return BodySpace::open(s); };
  k.describe_source = [](const std::string& source) {
    if (source.empty()) return std::string("on the neutral model");
    const auto& names = builtin_body_models();
    if (std::find(names.begin(), names.end(), source) != names.end()) {
      return "on the " + source + " model";
    }
    return "on " + std::filesystem::path(source).filename().string();
  };
  k.remembered_source = &remembered_body_model;
  k.make_source_panel = &make_body_source_panel;
  return k;
}

app::SpaceKind photo_kind() {
  app::SpaceKind k;
  k.name = "photo";
  k.label = "photo colours";
  k.source_noun = "Photo";
  k.source_option = "image";
  // Twelve edit parameters, always: the space has no other size.
  k.dimensions = 12;
  k.dimensions_fixed = true;
  // Nine cells keep every pair of edits visibly apart; a 5x5 grid could not (docs/benchmarks.md).
  k.grid_size = 3;
  k.file_extensions = {".png", ".jpg", ".jpeg"};
  k.open = [](const app::SpaceSettings& s) { return PhotoSpace::open(s); };
  k.describe_source = [](const std::string& source) {
    return source.empty() ? std::string("on the built-in photo")
                          : "on the photo " + std::filesystem::path(source).filename().string();
  };
  // A launch without --image starts on the built-in picture; New search offers the last one.
  k.remembered_source = [](const app::SourceMemory&) { return std::string(); };
  k.make_source_panel = &make_photo_source_panel;
  return k;
}

}  // namespace

const app::SpaceCatalogue& catalogue() {
  static const app::SpaceCatalogue kinds = [] {
    app::SpaceCatalogue c;
    c.add(body_kind());
    c.add(photo_kind());
    return c;
  }();
  return kinds;
}

const std::vector<std::string>& builtin_body_models() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> ordered{"neutral"};
    for (const auto& name : body::builtin_model_names()) {
      if (name != "neutral") ordered.push_back(name);
    }
    return ordered;
  }();
  return names;
}

app::SpaceSettings default_settings(const std::string& kind) {
  return catalogue().default_settings(kind);
}

std::unique_ptr<app::DesignSpace> open_space(const app::SpaceSettings& settings) {
  return catalogue().open(settings);
}

}  // namespace spaces
