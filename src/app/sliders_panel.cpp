#include "app/sliders_panel.hpp"

#include <imgui.h>

#include <algorithm>

namespace app {

void SlidersPanel::draw(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  const Eigen::VectorXd best = c.session().current_best();
  if (x_ && x_->size() != best.size()) x_.reset();
  Eigen::VectorXd x = x_ ? *x_ : best;
  bool changed = false;
  // The labels say what each component does ("1: longer legs 4.8 cm, taller"): they get the
  // larger part of the row, the slider the rest (the tooltip has the whole effect).
  const float label_width = ImGui::GetContentRegionAvail().x * 0.6f;
  for (int i = 0; i < c.space().dimensions(); ++i) {
    ImGui::PushID(i);
    float v = static_cast<float>(x[i]);
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - label_width));
    if (ImGui::SliderFloat(c.space().dimension_name(i).c_str(), &v, 0.0f, 1.0f, "%.3f")) {
      x[i] = std::clamp(static_cast<double>(v), 0.0, 1.0);
      changed = true;
    }
    if (ImGui::IsItemHovered()) {
      const std::string details = c.space().dimension_details(i);
      if (!details.empty()) ImGui::SetTooltip("%s", details.c_str());
    }
    ImGui::PopID();
  }
  if (changed) x_ = x;
  if (!c.holds().empty()) {
    // The sliders move every component freely; what is held is restored when the point is used.
    ImGui::TextWrapped("Held: %s. Use this moves the sliders' body onto the holds.",
                       c.holds_description().c_str());
  }
  ImGui::BeginDisabled(!x_ || c.busy());
  if (ImGui::Button("Use this")) {
    c.queue(intent::UsePoint{*x_});
    x_.reset();
  }
  ImGui::SameLine();
  if (ImGui::Button("Back to the current best")) x_.reset();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Discard the slider changes");
  }
}

}  // namespace app
