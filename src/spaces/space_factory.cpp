#include "spaces/space_factory.hpp"

#include <stdexcept>

#include "body/model_loader.hpp"
#include "spaces/body_space.hpp"
#include "spaces/photo_space.hpp"

namespace spaces {

const std::vector<std::string>& space_kinds() {
  static const std::vector<std::string> kinds{"body", "photo"};
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
  app::SpaceSettings s;
  s.kind = kind;
  s.dimensions = kind == "photo" ? 12 : 10;
  return s;
}

std::unique_ptr<app::DesignSpace> open_space(const app::SpaceSettings& settings) {
  if (settings.kind == "body") return BodySpace::open(settings);
  if (settings.kind == "photo") return PhotoSpace::open(settings);
  throw std::runtime_error("unknown design space '" + settings.kind + "' (known: body, photo)");
}

}  // namespace spaces
