// Opens a design space by kind ("body", "photo"): what the gallery, render-grid and the tests
// use instead of naming BodySpace or PhotoSpace.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/design_space.hpp"
#include "app/space_catalogue.hpp"

namespace spaces {

// Every kind of design space this program has, body first (the default): what the window and
// the command line are given.
const app::SpaceCatalogue& catalogue();

// Throws std::runtime_error for an unknown kind, or the space's own error (file, format).
std::unique_ptr<app::DesignSpace> open_space(const app::SpaceSettings& settings);

// The built-in body models a body search can start on, in the window picker's order: neutral
// (the default) first, then female and male. A SpaceSettings source of one of these names (or
// empty, for neutral) means that built-in model; any other source is a model file.
const std::vector<std::string>& builtin_body_models();

// What a new search in `kind` starts with: its dimension count (the body default 10).
app::SpaceSettings default_settings(const std::string& kind);

}  // namespace spaces
