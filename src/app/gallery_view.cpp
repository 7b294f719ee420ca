#include "app/gallery_view.hpp"

#include "app/previews_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace app {

namespace fs = std::filesystem;

namespace {

constexpr render::ViewPreset kPresets[] = {render::ViewPreset::kFront, render::ViewPreset::kSide,
                                           render::ViewPreset::kThreeQuarter};

}  // namespace

const std::vector<std::string>& side_panel_tabs() {
  static const std::vector<std::string> tabs{"measurements", "sliders", "history", "save",
                                             "new-search"};
  return tabs;
}

GalleryView::GalleryView(ViewOptions options, UiPrefs prefs, const SpaceCatalogue& catalogue)
    : options_(std::move(options)),
      prefs_(std::move(prefs)),
      catalogue_(catalogue),
      dialogs_(options_.file_dialog != "builtin"),
      widgets_(options_.report_layout),
      save_(options_.save_path, prefs_),
      new_search_(catalogue_, dialogs_, widgets_, prefs_) {
  const auto& tabs = side_panel_tabs();
  if (std::find(tabs.begin(), tabs.end(), prefs_.side_tab) == tabs.end()) {
    prefs_.side_tab = tabs.front();
  }
  set_preset(std::clamp(prefs_.view_preset, 0, 2));
}

GalleryView::~GalleryView() = default;

PanelContext GalleryView::context(GalleryController& c) {
  return PanelContext{c, prefs_, dialogs_, widgets_, catalogue_};
}

void GalleryView::release_gl() {
  cells_.clear();
  history_.release_gl();
  best_ = CellView{};
  start_ = CellView{};
  inspect_ = CellView{};
}

bool GalleryView::text_input_active() const {
  return ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantTextInput;
}

void GalleryView::set_preset(int index) {
  camera_.set_preset(kPresets[index]);
  active_preset_ = index;
  prefs_.view_preset = index;
  ++camera_version_;
}

void GalleryView::sync_space(GalleryController& c) {
  if (c.space_generation() == space_generation_) return;
  // Contents belong to the space that made them. This runs before the UI frame, so no texture
  // the UI has queued is freed here.
  release_gl();
  grid_.reset();
  framed_points_.clear();  // another space frames the same points differently
  sliders_.space_opened();
  space_generation_ = c.space_generation();
  new_search_.space_opened(c, prefs_);
  save_.space_opened(c.space(), prefs_);
}

void GalleryView::update_cells(GalleryController& c, float width, float height, float dpi) {
  sync_space(c);
  DesignSpace& space = c.space();
  const int n = c.session().settings().grid_size;
  // The toolbar's rows as the last frame drew them (the fonts decide), estimated at first.
  layout_ = compute_layout(width, height, n, options_.cell_size, toolbar_rows_drawn_);
  dpi = std::max(1.0f, dpi);
  dpi_ = dpi;
  cell_pixels_ = static_cast<int>(std::lround(dpi * layout_.cell));
  // What a person can tell apart depends on the size the cells are shown at.
  if (cell_pixels_ != sent_cell_pixels_) {
    c.queue(intent::SetCellPixels{cell_pixels_});
    sent_cell_pixels_ = cell_pixels_;
  }
  // Previews: two side by side above the tabs, at most 260 wide, in the space's aspect, and
  // no taller than a third of the side panel so that the tabs below keep room.
  const float aspect = std::max(0.2f, space.preview_aspect());
  float pw = std::min(260.0f, (layout_.side.w - 3 * kLayoutGap) / 2.0f);
  float ph = pw / aspect;
  const float max_h = std::max(80.0f, layout_.side.h * 0.34f);
  if (ph > max_h) {
    ph = max_h;
    pw = ph * aspect;
  }
  preview_w_ = static_cast<int>(pw);
  preview_h_ = static_cast<int>(ph);

  const auto& points = c.displayed_cells();
  if (cells_.size() != points.size()) cells_.resize(points.size());
  std::vector<Eigen::VectorXd> xs;
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells_[i].set_point(space, points[i].x, false);
    cells_[i].clamped = points[i].clamped;
    xs.push_back(points[i].x);
  }
  // Measured again only when the grid's points change (a zoom, a new plane, an animation
  // frame), not every frame.
  const auto same = [](const std::vector<Eigen::VectorXd>& a,
                       const std::vector<Eigen::VectorXd>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].size() != b[i].size() || a[i] != b[i]) return false;
    }
    return true;
  };
  if (!same(xs, framed_points_) || space.close_ups() != framed_close_ups_) {
    framed_close_ups_ = space.close_ups();
    const SpacePerception* perception = space.perception();
    const GridFrame frame = perception != nullptr ? perception->grid_frame(xs) : GridFrame{};
    framed_points_ = std::move(xs);
    if (std::abs(frame.scale - grid_frame_.scale) > 1e-4 ||
        std::abs(frame.pivot_m - grid_frame_.pivot_m) > 1e-4) {
      grid_frame_ = frame;
      ++grid_frame_version_;
    }
  }
  const Session& s = c.session();
  const auto& sliders = sliders_.point();
  const bool sliding = sliders && sliders->size() == space.dimensions();
  const Eigen::VectorXd current = s.current_best();
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells_[i].current =
        !sliding && points[i].x.size() == current.size() && (points[i].x - current).norm() < 1e-9;
  }
  best_.set_point(space, sliding ? *sliders : current, true);
  start_.set_point(space, s.start_point(), true);
  if (c.inspected() >= 0) {
    inspect_.set_point(space, s.history()[static_cast<std::size_t>(c.inspected())].chosen, true);
  }
  history_.update(s);
}

void GalleryView::orbit(float dx, float dy) {
  camera_.orbit(dx, dy);
  active_preset_ = -1;
  ++camera_version_;
  orbiting_ = true;  // drawn as during a drag (build() clears it again)
}

void GalleryView::draw_cells(GalleryController& c) {
  DesignSpace& space = c.space();
  const float dpi = dpi_;
  const float pw = static_cast<float>(preview_w_), ph = static_cast<float>(preview_h_);
  const float aspect = std::max(0.2f, space.preview_aspect());
  CellLook look;
  look.camera = space.uses_camera() ? &camera_ : nullptr;
  // While the grid moves, cells render without multisampling (a software rasterizer pays per
  // sample); the settled grid is drawn again with full antialiasing.
  const bool fast = c.animating() || grid_.dragging() || orbiting_;
  bool grid_drew = false;
  const render::Camera grid_camera = camera_.scaled_about_height(
      static_cast<float>(grid_frame_.scale), static_cast<float>(grid_frame_.pivot_m));
  CellLook grid_look = look;
  if (look.camera != nullptr) grid_look.camera = &grid_camera;
  // Both counters only grow, so their sum changes whenever either does.
  const int grid_camera_version = camera_version_ + grid_frame_version_;
  for (auto& cell : cells_) {
    grid_drew |=
        cell.draw(grid_look, grid_camera_version, cell_pixels_, cell_pixels_, options_.samples,
                  fast, options_.animation_scale, options_.animation_samples > 0);
  }
  const int pwx = static_cast<int>(std::lround(dpi * pw));
  const int phx = static_cast<int>(std::lround(dpi * ph));
  (c.inspected() >= 0 ? inspect_ : best_).draw(look, camera_version_, pwx, phx, options_.samples);
  CellLook muted = look;
  muted.muted = true;
  start_.draw(muted, camera_version_, pwx, phx, options_.samples);
  // A few new thumbnails a frame (a resumed long session has dozens), each drawn once, and
  // none in a frame that drew the grid: the grid comes first (launch, zoom, orbit).
  const int tw = static_cast<int>(std::lround(dpi * 58.0f));
  const int th = static_cast<int>(std::lround(dpi * 58.0f / aspect));
  history_.draw_thumbnails(space, tw, th, options_.samples, grid_drew ? 0 : 4);
}

void GalleryView::build(GalleryController& c, long frame) {
  PanelContext ctx = context(c);
  orbiting_ = false;
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("Sequential Gallery", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoBackground);  // glClear paints it, far cheaper
  ImGui::SetCursorScreenPos(ImVec2(layout_.toolbar.x, layout_.toolbar.y));
  draw_toolbar(c);
  {
    // The message lines wrap in the side column and stop at their rect (the whole text is
    // in the tooltip), so a long error never pushes the previews down.
    const LayoutRect& m = layout_.messages;
    ImGui::SetCursorScreenPos(ImVec2(m.x, m.y + 3));
    ImGui::PushClipRect(ImVec2(m.x, m.y), ImVec2(m.x + m.w, m.y + m.h), true);
    ImGui::PushTextWrapPos(m.x + m.w - ImGui::GetWindowPos().x);
    draw_messages(c);
    ImGui::PopTextWrapPos();
    ImGui::PopClipRect();
  }
  ImGui::SetCursorScreenPos(ImVec2(layout_.grid.x, layout_.grid.y));
  if (grid_.draw(ctx, layout_, cells_, best_.prepared.get(), camera_, frame,
                 options_.report_layout)) {
    active_preset_ = -1;  // a free orbit
    ++camera_version_;
  }
  ImGui::SetCursorScreenPos(ImVec2(layout_.side.x, layout_.side.y));
  ImGui::BeginChild("side", ImVec2(layout_.side.w, layout_.side.h), false);
  draw_side_panel(ctx);
  ImGui::EndChild();
  draw_questions(ctx);
  dialogs_.draw([this](const std::string& name) { widgets_.note(name); });
  ImGui::End();
  take_file_answer(ctx);
}

namespace {

// Lays the toolbar's groups out left to right and wraps a group that would cross the toolbar's
// right edge onto the next row (the side column is narrower than the items at small windows).
class ToolbarFlow {
 public:
  ToolbarFlow(float left, float right) : left_(left), right_(right) {}
  // Before a group `width` wide: on this row if it fits, else on the next. True when it stays
  // on this row (a separator belongs before it then).
  bool next(float width) {
    if (first_) {
      first_ = false;
      return false;
    }
    const float x = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x;
    if (x + width > right_) {
      // ImGui starts a new row at the window's left edge, under the grid: move it back.
      ImGui::SetCursorScreenPos(ImVec2(left_, ImGui::GetCursorScreenPos().y));
      ++rows_;
      return false;
    }
    ImGui::SameLine();
    return true;
  }
  // The same, for a group that a dimmed "|" separates from what comes before on its row.
  void next_separated(float width) {
    const float bar = ImGui::CalcTextSize("|").x + ImGui::GetStyle().ItemSpacing.x;
    if (!next(bar + width)) return;
    ImGui::TextDisabled("|");
    ImGui::SameLine();
  }
  int rows() const { return rows_; }

 private:
  float left_, right_;
  bool first_ = true;
  int rows_ = 1;
};

float button_width(const char* label) {
  return ImGui::CalcTextSize(label).x + 2 * ImGui::GetStyle().FramePadding.x;
}

float radio_width(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label).x;
}

}  // namespace

void GalleryView::draw_toolbar(GalleryController& c) {
  ToolbarFlow flow(layout_.toolbar.x, layout_.toolbar.x + layout_.toolbar.w);
  const auto button = [&flow](const char* label, bool enabled, const char* tip) {
    flow.next(button_width(label));
    ImGui::BeginDisabled(!enabled);
    const bool pressed = ImGui::Button(label);
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", tip);
    return pressed;
  };
  if (button("Undo click", c.can_undo_click(), "Take back the last click (Backspace / Ctrl+Z)")) {
    c.queue(intent::UndoClick{});
  }
  if (button("Undo plane", c.can_undo_plane(), "Go back to the start of the last finished plane")) {
    c.queue(intent::UndoPlane{});
  }
  if (button("Redo", c.can_redo(), "Redo what Undo took back (Ctrl+Y / Ctrl+Shift+Z)")) {
    c.queue(intent::Redo{});
  }
  if (button("Start over", !c.busy() && c.has_progress(),
             "Discard the clicks and the history, after asking (Redo brings them back)")) {
    confirm_start_over_ = true;
  }
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  if (c.space().uses_camera()) {
    const char* labels[] = {"Front", "Side", "3/4"};
    float width = ImGui::CalcTextSize("View:").x;
    for (const char* label : labels) width += spacing + radio_width(label);
    // The checkbox is as wide as a radio button with the same label.
    width += spacing + radio_width("Close-ups");
    flow.next_separated(width);
    ImGui::TextUnformatted("View:");
    for (int i = 0; i < 3; ++i) {
      ImGui::SameLine();
      if (ImGui::RadioButton(labels[i], active_preset_ == i)) set_preset(i);
    }
    ImGui::SameLine();
    // What the grid shows (the controller applies the remembered choice to every space).
    bool close_ups = c.options().close_ups;
    if (ImGui::Checkbox("Close-ups", &close_ups)) {
      prefs_.close_ups = close_ups;
      c.queue(intent::SetCloseUps{close_ups});
    }
    widgets_.note("toolbar:close-ups");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "Frame each grid on the part of the body where its nine bodies differ (after the "
          "first zoom mostly the trunk, shown up to twice as large), or show them whole.\n"
          "The zoom keeps the cells visibly different as framed.");
    }
  }
  const auto& s = c.session().settings();
  char plane[64];
  std::snprintf(plane, sizeof plane, "Plane %d   click %d of %d", c.session().planes_done() + 1,
                std::min(c.session().clicks_on_plane() + (c.busy() ? 0 : 1), s.zoom_levels),
                s.zoom_levels);
  flow.next_separated(ImGui::CalcTextSize(plane).x);
  ImGui::TextUnformatted(plane);
  const SpaceKind* kind = catalogue_.find(c.space().settings().kind);
  const std::string source = (kind != nullptr ? kind->source_noun : std::string("Source")) + ": " +
                             c.space().source_label();
  flow.next_separated(ImGui::CalcTextSize(source.c_str()).x);
  ImGui::TextUnformatted(source.c_str());
  widgets_.note("toolbar:model");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.space().description().c_str());
  toolbar_rows_drawn_ = flow.rows();
}

void GalleryView::draw_messages(const GalleryController& c) {
  // A failing autosave stays on screen until a save works again: the user must know that
  // clicks are not being kept.
  if (c.open_elsewhere()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1));
    ImGui::TextUnformatted(
        "READ-ONLY -- this search is open in another window, so nothing here is saved. Close "
        "that window to continue it here.");
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.autosave_problem().c_str());
    return;
  }
  if (!c.autosave_problem().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1));
    ImGui::Text("AUTOSAVE IS FAILING -- your clicks are not being saved: %s",
                c.autosave_problem().c_str());
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.autosave_problem().c_str());
    return;
  }
  const Message& m = c.message();
  if (m.text.empty()) {
    ImGui::TextDisabled("Click the cell you like best; each click zooms in around it.");
    return;
  }
  const ImVec4 colour = m.kind == MessageKind::kError     ? ImVec4(1.0f, 0.45f, 0.4f, 1)
                        : m.kind == MessageKind::kSuccess ? ImVec4(0.5f, 0.9f, 0.5f, 1)
                                                          : ImVec4(0.85f, 0.85f, 0.9f, 1);
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextUnformatted(m.text.c_str());
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m.text.c_str());
}

void GalleryView::draw_side_panel(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  const bool inspecting = c.inspected() >= 0;
  char title[64];
  if (inspecting) {
    std::snprintf(title, sizeof title, "Plane %d choice", c.inspected() + 1);
  } else if (sliders_.point()) {
    std::snprintf(title, sizeof title, "Sliders (not chosen yet)");
  } else {
    std::snprintf(title, sizeof title, "Current best");
  }
  // The current best is not always the cell picked last, which surprises people: say why.
  const bool best = !inspecting && !sliders_.point();
  draw_previews(title, inspecting ? inspect_ : best_, start_, static_cast<float>(preview_w_),
                static_cast<float>(preview_h_),
                best ? "What Save writes. While you zoom in: the cell you clicked last. After each "
                       "plane: the search's estimate of what you have in mind from all your "
                       "clicks so far, which weighs every choice and so can differ from your "
                       "last pick (in the benchmarks it is nearer the target than the last "
                       "pick)."
                     : "");
  if (inspecting && ImGui::Button("Back to current best")) c.queue(intent::Inspect{-1});
  // The tabs take what the previews and the footer leave; a tab longer than that scrolls
  // inside itself, so the previews, the tab names and the footer stay in view.
  // The footer (design space, keys) takes what its wrapped text needs at this width; a fixed
  // three lines cut the keys off in a narrow side column.
  char keys[256];
  std::snprintf(keys, sizeof keys,
                "Keys: %s pick a cell, Backspace/Ctrl+Z undo, Ctrl+Y redo, Ctrl+S save, "
                "Ctrl+Q quit; Shift over a cell: all it changes%s",
                c.session().settings().grid_size == 3 ? "1-9" : "A-Y",
                c.space().uses_camera() ? "; drag a cell to orbit" : "");
  const std::string design = "Design space: " + c.space().description();
  const ImGuiStyle& style = ImGui::GetStyle();
  const float wrap = ImGui::GetContentRegionAvail().x;
  const float footer = 3 * style.ItemSpacing.y +
                       ImGui::CalcTextSize(design.c_str(), nullptr, false, wrap).y +
                       ImGui::CalcTextSize(keys, nullptr, false, wrap).y;
  ImGui::BeginChild("tabs", ImVec2(0, std::max(120.0f, ImGui::GetContentRegionAvail().y - footer)),
                    false);
  draw_tabs(ctx);
  ImGui::EndChild();
  ImGui::Separator();
  ImGui::PushStyleColor(ImGuiCol_Text, style.Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", design.c_str());
  ImGui::PopStyleColor();
  ImGui::TextWrapped("%s", keys);
}

void GalleryView::draw_tabs(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  if (prefs_.side_tab != shown_tab_) pending_tab_ = prefs_.side_tab;
  if (!ImGui::BeginTabBar("side-tabs")) return;
  const bool inspecting = c.inspected() >= 0;
  const SpaceMeasurements* measurements = c.space().measurements();
  const bool has_measurements =
      measurements != nullptr && !measurements->measurement_names().empty();
  std::string current;
  for (const std::string& tab : side_panel_tabs()) {
    const char* label = tab == "measurements" ? (has_measurements ? "Measurements" : "Details")
                        : tab == "sliders"    ? "Sliders"
                        : tab == "history"    ? "History"
                        : tab == "save"       ? "Save"
                                              : "New search";
    const ImGuiTabItemFlags flags = pending_tab_ == tab ? ImGuiTabItemFlags_SetSelected : 0;
    const bool open = ImGui::BeginTabItem(label, nullptr, flags);
    widgets_.note("tab:" + tab);
    if (!open) continue;
    current = tab;
    ImGui::BeginChild("content", ImVec2(0, 0), false);
    if (tab == "measurements") {
      measurements_.draw(ctx, (inspecting ? inspect_ : best_).prepared.get(), start_.prepared.get(),
                         grid_.hovered_details(), inspecting);
    } else if (tab == "sliders") {
      sliders_.draw(ctx);
    } else if (tab == "history") {
      history_.draw(ctx);
    } else if (tab == "save") {
      save_.draw(ctx);
      ImGui::Separator();
      ImGui::TextWrapped("Your clicks are kept in %s%s", c.session_path().string().c_str(),
                         c.autosave_enabled() ? "" : " (autosave OFF)");
    } else {
      new_search_.draw(ctx);
    }
    ImGui::EndChild();
    ImGui::EndTabItem();
  }
  ImGui::EndTabBar();
  if (!pending_tab_.empty() && current == pending_tab_) pending_tab_.clear();
  shown_tab_ = current;
  if (pending_tab_.empty() && !current.empty()) prefs_.side_tab = current;
}

void GalleryView::draw_questions(PanelContext& ctx) {
  GalleryController& c = ctx.c;
  if (c.resume_candidate() != nullptr) {
    const bool elsewhere = c.open_elsewhere();
    const char* title = elsewhere ? "Open in another window" : "Resume session?";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text(elsewhere ? "This search is open in another window: %s"
                            : "A previous session was found: %s",
                  c.session_path().string().c_str());
      ImGui::TextUnformatted(c.resume_description().c_str());
      const std::string instead = c.asked_kind_instead();
      if (!instead.empty()) {
        ImGui::Text("You asked for a %s search: start it, or resume the %s search?",
                    instead.c_str(), c.resume_kind().c_str());
      }
      if (elsewhere) {
        ImGui::TextUnformatted(
            "This window saves nothing, so the other one loses no clicks. Close the other window "
            "to continue the search here.");
      }
      const std::string resume_label =
          elsewhere ? "View read-only"
                    : (instead.empty() ? "Resume" : "Resume the " + c.resume_kind() + " search");
      if (ImGui::Button(resume_label.c_str(), ImVec2(instead.empty() ? 160 : 220, 0))) {
        c.queue(intent::Resume{});
        ImGui::CloseCurrentPopup();
      }
      ImGui::SameLine();
      const std::string start_label =
          elsewhere ? "New search (not saved)"
                    : (instead.empty() ? "Start new" : "Start the " + instead + " search");
      if (ImGui::Button(start_label.c_str(), ImVec2(instead.empty() ? 160 : 220, 0))) {
        c.queue(intent::StartNew{});
        ImGui::CloseCurrentPopup();
      }
      ImGui::EndPopup();
    }
    return;
  }
  if (confirm_start_over_) {
    if (!ImGui::IsPopupOpen("Start over?")) ImGui::OpenPopup("Start over?");
    if (ImGui::BeginPopupModal("Start over?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("Discard all preference data and the history? (Redo brings them back.)");
      if (ImGui::Button("Start over", ImVec2(140, 0))) {
        c.queue(intent::StartOver{});
        confirm_start_over_ = false;
        ImGui::CloseCurrentPopup();
      }
      ImGui::SameLine();
      if (ImGui::Button("Cancel", ImVec2(140, 0))) {
        confirm_start_over_ = false;
        ImGui::CloseCurrentPopup();
      }
      ImGui::EndPopup();
    }
  }
  new_search_.draw_question(ctx);
  save_.draw_question(ctx);
}

void GalleryView::take_file_answer(PanelContext& ctx) {
  const auto answer = dialogs_.take_answer();
  if (!answer) return;
  if (answer->tag == "save") {
    save_.file_chosen(ctx, answer->path);
  } else {
    new_search_.file_chosen(answer->path.string());
  }
}

void GalleryView::quick_save(GalleryController& c) {
  PanelContext ctx = context(c);
  save_.quick_save(ctx);
}

void GalleryView::open_dropped(GalleryController& c, const std::string& path) {
  PanelContext ctx = context(c);
  new_search_.open_dropped(ctx, path);
}

void GalleryView::press_cell(GalleryController& c, int index) {
  const int n = c.session().settings().grid_size;
  if (index < 0 || index >= n * n) return;
  c.queue(intent::ClickCell{index % n, index / n});
}

}  // namespace app
