#include "app/previews_panel.hpp"

#include <imgui.h>

#include "app/panel_context.hpp"

namespace app {

namespace {

void preview(const char* title, const CellView& cell, const ImVec2& size) {
  ImGui::BeginGroup();
  ImGui::TextUnformatted(title);
  if (cell.fbo.texture() != 0) {
    ImGui::Image(texture_id(cell.fbo.texture()), size, ImVec2(0, 1), ImVec2(1, 0));
  } else {
    ImGui::Dummy(size);
  }
  ImGui::EndGroup();
}

}  // namespace

void draw_previews(const std::string& shown_title, const CellView& shown, const CellView& start,
                   float width, float height, const std::string& shown_tooltip) {
  const ImVec2 size(width, height);
  preview(shown_title.c_str(), shown, size);
  if (!shown_tooltip.empty() && ImGui::IsItemHovered()) {
    // Wrapped to the preview's width and a little more: one line ran off the window.
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(shown_tooltip.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  ImGui::SameLine();
  // The body the search began with, as it was (not projected onto any holds in force): holds
  // shape what the grid shows from now on; the start is the reference the user compares with
  // (the measurements' "start" column reads its own values, e.g. the height before it was held
  // at another).
  preview("Started from", start, size);
}

}  // namespace app
