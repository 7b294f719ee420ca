#include "app/history_panel.hpp"

#include <imgui.h>

#include <algorithm>

namespace app {

HistoryPanel::HistoryPanel() {
  camera_.set_preset(render::ViewPreset::kFront);
}

void HistoryPanel::update(const Session& session) {
  const auto& history = session.history();
  if (thumbnails_.size() != history.size()) thumbnails_.resize(history.size());
  for (std::size_t i = 0; i < thumbnails_.size(); ++i) {
    const Eigen::VectorXd& chosen = history[i].chosen;
    if (thumbnails_[i].x.size() != chosen.size() || thumbnails_[i].x != chosen) {
      thumbnails_[i].x = chosen;
      thumbnails_[i].drawn = false;
    }
  }
}

void HistoryPanel::draw_thumbnails(DesignSpace& space, int width, int height, int samples,
                                   int budget) {
  CellLook front;
  front.camera = space.uses_camera() ? &camera_ : nullptr;
  for (auto& t : thumbnails_) {
    if (t.drawn && t.fbo.width() == width && t.fbo.height() == height) continue;
    if (budget-- <= 0) break;
    CellView once;
    once.set_point(space, t.x, false);
    once.draw(front, 0, width, height, samples);
    t.fbo = std::move(once.fbo);
    t.drawn = true;
    ++draws_;
  }
}

void HistoryPanel::draw(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  const int planes = c.session().planes_done();
  ImGui::Text("%d finished plane%s (click one to inspect it)", planes, planes == 1 ? "" : "s");
  const float aspect = std::max(0.2f, c.space().preview_aspect());
  const ImVec2 thumb(58.0f, 58.0f / aspect);
  // Rows that wrap to the tab's width: a long session scrolls down, never off to the side.
  const float step = thumb.x + 10.0f;
  const int per_row = std::max(1, static_cast<int>(ImGui::GetContentRegionAvail().x / step));
  for (std::size_t i = 0; i < thumbnails_.size(); ++i) {
    if (i % static_cast<std::size_t>(per_row) != 0) ImGui::SameLine();
    ImGui::PushID(static_cast<int>(i));
    ImGui::BeginGroup();
    const bool selected = c.inspected() == static_cast<int>(i);
    if (selected) ImGui::PushStyleColor(ImGuiCol_Button, IM_COL32(255, 170, 40, 255));
    if (ImGui::ImageButton(texture_id(thumbnails_[i].fbo.texture()), thumb, ImVec2(0, 1),
                           ImVec2(1, 0), 2)) {
      c.queue(intent::Inspect{selected ? -1 : static_cast<int>(i)});
    }
    if (selected) ImGui::PopStyleColor();
    ImGui::Text("#%zu", i + 1);
    ImGui::EndGroup();
    ImGui::PopID();
  }
  if (thumbnails_.empty()) ImGui::TextDisabled("the choice of every finished plane appears here");
}

}  // namespace app
