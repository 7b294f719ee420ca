#include "app/save_panel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

namespace app {

namespace fs = std::filesystem;

fs::path default_save_folder() {
  // The user's documents folder when there is one (XDG's default name), else the home folder;
  // never the folder the program happened to be started from.
  const char* home = std::getenv("HOME");
  if (home == nullptr || home[0] != '/') return fs::current_path();
  std::error_code ec;
  const fs::path documents = fs::path(home) / "Documents";
  return fs::is_directory(documents, ec) ? documents : fs::path(home);
}

SavePanel::SavePanel(const std::string& path, const UiPrefs& prefs) : path_(path) {
  if (path_.empty() && !prefs.save_name.empty()) {
    path_ = (fs::path(prefs.save_folder) / prefs.save_name).string();
  }
}

void SavePanel::space_opened(const DesignSpace& space, const UiPrefs& prefs) {
  const std::string ext = fs::path(space.default_export_name()).extension().string();
  if (path_.empty() || fs::path(path_).extension() != ext) {
    const fs::path folder =
        prefs.save_folder.empty() ? default_save_folder() : fs::path(prefs.save_folder);
    path_ = (folder / space.default_export_name()).string();
  }
}

void SavePanel::draw(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  ImGui::TextWrapped("Save the shown %s (%s)", c.inspected() >= 0 ? "choice" : "current best",
                     c.space().export_hint().c_str());
  ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 150.0f));
  ImGui::InputText("##savepath", &path_);
  ImGui::SameLine();
  if (ImGui::Button("Save##quick")) quick_save(ctx);
  ctx.widgets.note("save:quick");
  ImGui::SameLine();
  if (ImGui::Button("Save as...")) open_dialog(ctx);
  // Where Save writes, in full: a relative name is relative to the folder the program was
  // started from, which the field alone does not say.
  std::error_code ec;
  const fs::path target = path_.empty() ? fs::path() : fs::absolute(path_, ec);
  if (!target.empty()) ImGui::TextWrapped("saves to %s", target.string().c_str());
  if (!c.last_export().empty()) {
    ImGui::TextDisabled("last saved: %s", c.last_export().string().c_str());
  }
}

void SavePanel::draw_question(PanelContext& ctx) {
  if (!confirm_overwrite_) return;
  if (!ImGui::IsPopupOpen("Replace file?")) ImGui::OpenPopup("Replace file?");
  if (!ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::Text("%s already exists.", confirm_overwrite_->string().c_str());
  if (ImGui::Button("Replace it", ImVec2(140, 0))) {
    ctx.c.queue(intent::Export{*confirm_overwrite_});
    confirm_overwrite_.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(140, 0))) {
    confirm_overwrite_.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void SavePanel::quick_save(PanelContext& ctx) {
  if (path_.empty()) {
    open_dialog(ctx);
    return;
  }
  request_export(ctx, path_);
}

void SavePanel::open_dialog(PanelContext& ctx) {
  const fs::path current =
      path_.empty() ? fs::path(ctx.c.space().default_export_name()) : fs::path(path_);
  ctx.dialogs.open(FileRequest{"save", "Save as", true, {}, "", current});
}

void SavePanel::file_chosen(PanelContext& ctx, const fs::path& path) {
  request_export(ctx, path);
}

void SavePanel::request_export(PanelContext& ctx, const fs::path& path) {
  path_ = path.string();
  std::error_code ec;
  ctx.prefs.save_folder = fs::absolute(path, ec).parent_path().string();
  ctx.prefs.save_name = path.filename().string();
  // Ask before replacing a file, except the one this search just saved (saving again).
  if (fs::exists(path, ec) && fs::absolute(path, ec) != fs::absolute(ctx.c.last_export(), ec)) {
    confirm_overwrite_ = path;
    std::cout << "[gallery] asking before replacing " << path.string() << std::endl;
    return;
  }
  ctx.c.queue(intent::Export{path});
}

}  // namespace app
