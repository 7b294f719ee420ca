#include "app/new_search_panel.hpp"

#include <imgui.h>

#include <algorithm>

#include "sps/plane_search.hpp"

namespace app {

NewSearchPanel::NewSearchPanel(const SpaceCatalogue& catalogue, FileDialogs& dialogs,
                               WidgetNotes& widgets, const UiPrefs& prefs)
    : catalogue_(catalogue), dialogs_(dialogs), widgets_(widgets), memory_(prefs.sources) {
  select_kind(catalogue_.default_kind());
}

SourcePanel* NewSearchPanel::panel(const std::string& kind) {
  auto it = panels_.find(kind);
  if (it == panels_.end()) {
    const SpaceKind& k = catalogue_.get(kind);
    it = panels_.emplace(kind, k.make_source_panel ? k.make_source_panel(memory_) : nullptr).first;
  }
  return it->second.get();
}

void NewSearchPanel::select_kind(const SpaceKind& kind) {
  if (kind_ == kind.name) return;
  kind_ = kind.name;
  dims_ = kind.dimensions;
  grid_ = kind.grid_size;
}

void NewSearchPanel::space_opened(const GalleryController& c, UiPrefs& prefs) {
  const SpaceSettings s = c.space().settings();
  const SpaceKind* kind = catalogue_.find(s.kind);
  if (kind == nullptr) return;
  const bool asked_here =
      requested_ && requested_->kind == s.kind && requested_->source == s.source;
  requested_.reset();
  select_kind(*kind);
  if (SourcePanel* p = panel(kind->name)) p->opened(s.source, asked_here, prefs.sources);
  dims_ = s.dimensions;
  grid_ = c.session().settings().grid_size;
  zoom_ = c.session().settings().zoom_levels;
}

void NewSearchPanel::draw(PanelContext& ctx) {
  ImGui::TextUnformatted("Design:");
  for (const SpaceKind& k : catalogue_.kinds()) {
    ImGui::SameLine();
    if (ImGui::RadioButton(k.label.c_str(), kind_ == k.name)) select_kind(k);
    widgets_.note("kind:" + k.name);
  }
  const SpaceKind& kind = catalogue_.get(kind_);
  SourcePanel* source = panel(kind_);
  if (source != nullptr) source->draw(*this);
  if (!kind.dimensions_fixed) {
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt("dimensions", &dims_);
    dims_ = std::clamp(dims_, 1, sps::kMaxSearchDims);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("How many of the model's components the search explores (its first ones)");
    }
  }
  ImGui::TextUnformatted("Grid");
  ImGui::SameLine();
  ImGui::RadioButton("3x3", &grid_, 3);
  ImGui::SameLine();
  ImGui::RadioButton("5x5", &grid_, 5);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::InputInt("clicks/plane", &zoom_);
  zoom_ = std::clamp(zoom_, 1, 8);
  const bool ready = source == nullptr || source->chosen_source().has_value();
  ImGui::BeginDisabled(ctx.c.busy() || !ready);
  if (ImGui::Button("Start a new search")) start(ctx);
  widgets_.note("new-search");
  ImGui::EndDisabled();
}

void NewSearchPanel::start(PanelContext& ctx) {
  SourcePanel* source = panel(kind_);
  const auto chosen = source != nullptr ? source->chosen_source() : std::optional<std::string>("");
  if (!chosen) return;
  request(ctx, *chosen);
}

void NewSearchPanel::open_dropped(PanelContext& ctx, const std::string& path) {
  const SpaceKind* kind = catalogue_.kind_for_file(path);
  select_kind(kind != nullptr ? *kind : catalogue_.default_kind());
  ctx.prefs.side_tab = "new-search";
  grid_ = catalogue_.get(kind_).grid_size;
  SourcePanel* source = panel(kind_);
  if (source != nullptr) source->use_file(path);
  // A file the kind cannot use still starts: the space's own error names the file and the
  // problem, and the current search stays.
  request(ctx, source != nullptr ? source->chosen_source().value_or(path) : path);
}

void NewSearchPanel::request(PanelContext& ctx, const std::string& source) {
  SpaceSettings space = catalogue_.default_settings(kind_);
  if (!catalogue_.get(kind_).dimensions_fixed) space.dimensions = dims_;
  space.source = source;
  requested_ = space;
  const intent::Open o{space, grid_, zoom_};
  if (ctx.c.has_progress()) {
    confirm_open_ = o;  // ask first: a search is work
  } else {
    ctx.c.queue(o);
  }
}

void NewSearchPanel::draw_question(PanelContext& ctx) {
  if (!confirm_open_) return;
  GalleryController& c = ctx.c;
  if (!ImGui::IsPopupOpen("Start a new search?")) ImGui::OpenPopup("Start a new search?");
  if (!ImGui::BeginPopupModal("Start a new search?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    return;
  }
  ImGui::Text("The current search has %d finished plane(s) and %d click(s).",
              c.session().planes_done(), c.session().clicks_on_plane());
  const SpaceKind& kind = catalogue_.get(confirm_open_->space.kind);
  const std::string what =
      kind.describe_source ? kind.describe_source(confirm_open_->space.source) : kind.label;
  ImGui::Text("A new search %s replaces it; its session file is kept as %s.previous.", what.c_str(),
              c.session_path().filename().string().c_str());
  if (ImGui::Button("Start the new search", ImVec2(200, 0))) {
    c.queue(*confirm_open_);
    confirm_open_.reset();
    ImGui::CloseCurrentPopup();
  }
  widgets_.note("confirm:start");
  ImGui::SameLine();
  if (ImGui::Button("Keep searching", ImVec2(160, 0))) {
    confirm_open_.reset();
    requested_.reset();
    ImGui::CloseCurrentPopup();
  }
  widgets_.note("confirm:keep");
  ImGui::EndPopup();
}

void NewSearchPanel::file_chosen(const std::string& path) {
  if (SourcePanel* source = panel(kind_)) source->use_file(path);
}

std::string NewSearchPanel::source_choice() const {
  const auto it = panels_.find(kind_);
  return it == panels_.end() || !it->second ? std::string() : it->second->choice();
}

void NewSearchPanel::choose_source(const std::string& choice) {
  if (SourcePanel* source = panel(kind_)) source->choose(choice, *this);
}

void NewSearchPanel::use_source_file(const std::string& path) {
  file_chosen(path);
}

void NewSearchPanel::browse(const std::string& title, const std::vector<std::string>& extensions,
                            const std::filesystem::path& start) {
  std::string label = catalogue_.get(kind_).label;
  dialogs_.open(FileRequest{"source", title, false, extensions, label, start});
}

}  // namespace app
