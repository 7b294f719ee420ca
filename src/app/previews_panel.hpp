// The side panel's two previews: the shown body or photo (the current best, an inspected
// plane's choice, or the sliders' point) beside the one the search started from.
#pragma once

#include <string>

#include "app/cell_view.hpp"

namespace app {

// `shown_tooltip` (may be empty): what the shown preview is, when the pointer is over it.
void draw_previews(const std::string& shown_title, const CellView& shown, const CellView& start,
                   float width, float height, const std::string& shown_tooltip = {});

}  // namespace app
