#include "spaces/space_factory.hpp"

#include <stdexcept>

#include "spaces/body_space.hpp"

namespace spaces {

const std::vector<std::string>& space_kinds() {
  static const std::vector<std::string> kinds{"body"};
  return kinds;
}

app::SpaceSettings default_settings(const std::string& kind) {
  app::SpaceSettings s;
  s.kind = kind;
  s.dimensions = 10;
  return s;
}

std::unique_ptr<app::DesignSpace> open_space(const app::SpaceSettings& settings) {
  if (settings.kind == "body") return BodySpace::open(settings);
  throw std::runtime_error("unknown design space '" + settings.kind + "' (known: body)");
}

}  // namespace spaces
