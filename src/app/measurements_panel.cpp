#include "app/measurements_panel.hpp"

#include <imgui.h>

namespace app {

void MeasurementsPanel::draw(PanelContext& ctx, const PreparedCell* shown,
                             const PreparedCell* start, const PreparedCell* hovered,
                             bool inspecting) {
  GalleryController& c = ctx.c;
  const SpaceMeasurements* measurements = c.space().measurements();
  const auto names =
      measurements != nullptr ? measurements->measurement_names() : std::vector<std::string>{};
  if (names.empty()) {
    if (shown != nullptr && start != nullptr) {
      c.space().draw_inspector(*shown, inspecting ? "chosen" : "current", start, "start");
    }
    return;
  }
  // Typed targets and the units survive a relaunch (ui.json).
  if (state_.target_text.size() != names.size()) {
    state_.target_text.assign(names.size(), "");
    for (std::size_t i = 0; i < names.size(); ++i) {
      const auto it = ctx.prefs.typed_targets.find(names[i]);
      if (it != ctx.prefs.typed_targets.end()) state_.target_text[i] = it->second;
    }
    state_.imperial = ctx.prefs.imperial;
  }
  const auto request =
      measurements->draw_measurement_panel(shown, start, hovered, c.holds(), state_);
  for (std::size_t i = 0; i < names.size() && i < state_.target_text.size(); ++i) {
    if (state_.target_text[i].empty()) {
      ctx.prefs.typed_targets.erase(names[i]);
    } else {
      ctx.prefs.typed_targets[names[i]] = state_.target_text[i];
    }
  }
  ctx.prefs.imperial = state_.imperial;
  if (request.holds) c.queue(intent::SetHolds{*request.holds});
  if (request.targets) c.queue(intent::GoToTargets{*request.targets});
  if (!c.holds().empty()) {
    ImGui::TextColored(ImVec4(0.55f, 0.8f, 1.0f, 1.0f), "Held in every cell: %s",
                       c.holds_description().c_str());
  }
}

}  // namespace app
