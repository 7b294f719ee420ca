// The New-search panel's source pickers of the two spaces: a body model (built in or a file)
// and a photo (built in or a file). Registered with their kinds in space_factory.cpp.
#pragma once

#include <memory>

#include "app/space_catalogue.hpp"

namespace spaces {

std::unique_ptr<app::SourcePanel> make_body_source_panel(const app::SourceMemory& memory);
std::unique_ptr<app::SourcePanel> make_photo_source_panel(const app::SourceMemory& memory);

// The source a body search starts on when none is given: the model last started in the
// window, at first neutral.
std::string remembered_body_model(const app::SourceMemory& memory);

}  // namespace spaces
