#include "app/panel_context.hpp"

#include <imgui.h>

#include <iostream>

namespace app {

void WidgetNotes::note(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const LayoutRect r{a.x, a.y, b.x - a.x, b.y - a.y};
  LayoutRect& known = rects_[name];
  const bool moved = known.x != r.x || known.y != r.y || known.w != r.w || known.h != r.h;
  known = r;
  if (moved && report_) {
    std::cout << "[layout] widget " << name << " " << r.x << " " << r.y << " " << r.w << " " << r.h
              << std::endl;
  }
}

std::optional<LayoutRect> WidgetNotes::find(const std::string& name) const {
  const auto it = rects_.find(name);
  if (it == rects_.end()) return std::nullopt;
  return it->second;
}

}  // namespace app
