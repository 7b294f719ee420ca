#include "app/gallery_view.hpp"

#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "spaces/space_factory.hpp"
#include "sps/plane_search.hpp"

namespace app {

namespace fs = std::filesystem;

namespace {

ImTextureID texture_id(GLuint texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture));
}

void disable_blending(const ImDrawList* /*list*/, const ImDrawCmd* /*cmd*/) {
  glDisable(GL_BLEND);
}

constexpr render::ViewPreset kPresets[] = {render::ViewPreset::kFront, render::ViewPreset::kSide,
                                           render::ViewPreset::kThreeQuarter};

// The desktop's own save dialog, if one is installed: zenity (GNOME) or kdialog (KDE).
std::string find_program(const char* name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  std::string dirs = path;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return "";
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) {
    if (ch == '\'') {
      q += "'\\''";
    } else {
      q += ch;
    }
  }
  return q + "'";
}

std::optional<std::string> run_dialog(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (status != 0 || out.empty()) return std::nullopt;  // cancelled
  return out;
}

bool is_builtin_body_model(const std::string& name) {
  const auto& names = spaces::builtin_body_models();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

// "on the female model", "on my_model.npz", "on the photo beach.jpg": for the question.
std::string what_is_opened(const SpaceSettings& s) {
  const std::string file = fs::path(s.source).filename().string();
  if (s.kind == "body") {
    if (s.source.empty()) return "on the neutral model";
    return is_builtin_body_model(s.source) ? "on the " + s.source + " model" : "on " + file;
  }
  return s.source.empty() ? "on the built-in photo" : "on the photo " + file;
}

}  // namespace

fs::path default_save_folder() {
  // The user's documents folder when there is one (XDG's default name), else the home folder;
  // never the folder the program happened to be started from.
  const char* home = std::getenv("HOME");
  if (home == nullptr || home[0] != '/') return fs::current_path();
  std::error_code ec;
  const fs::path documents = fs::path(home) / "Documents";
  return fs::is_directory(documents, ec) ? documents : fs::path(home);
}

GalleryView::GalleryView(ViewOptions options, UiPrefs prefs)
    : options_(std::move(options)), prefs_(std::move(prefs)) {
  thumbnail_camera_.set_preset(render::ViewPreset::kFront);
  open_model_file_ = prefs_.body_model_file;
  select_model_source(prefs_.body_model);
  open_photo_file_ = prefs_.photo_file;
  set_preset(std::clamp(prefs_.view_preset, 0, 2));
  save_path_ = options_.save_path;
  if (save_path_.empty() && !prefs_.save_name.empty()) {
    save_path_ = (fs::path(prefs_.save_folder) / prefs_.save_name).string();
  }
}

GalleryView::~GalleryView() = default;

void GalleryView::release_gl() {
  cells_.clear();
  history_.clear();
  best_ = CellView{};
  start_ = CellView{};
  inspect_ = CellView{};
}

std::string GalleryView::cell_label(int index, int n) {
  if (n == 3) return std::to_string(index + 1);
  if (index >= 0 && index < 26) return std::string(1, static_cast<char>('A' + index));
  return std::to_string(index + 1);
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
  hover_details_.reset();
  space_generation_ = c.space_generation();
  const SpaceSettings s = c.space().settings();
  open_kind_ = s.kind;
  open_source_ = s.kind == "body" ? std::string() : s.source;
  if (s.kind == "photo" && !s.source.empty()) {
    // A picture that opened is the one offered next time (also after a relaunch).
    open_photo_file_ = s.source;
    prefs_.photo_file = s.source;
  }
  if (s.kind == "body") {
    // A body search this view started has opened: its model is the one to start with next
    // time. (A session resumed or a --model given on the command line is not a choice made
    // here, and a file that failed to load never gets this far.)
    if (requested_model_ && *requested_model_ == s.source) {
      prefs_.body_model = s.source.empty() ? "neutral" : s.source;
      if (!is_builtin_body_model(prefs_.body_model)) prefs_.body_model_file = s.source;
    }
    select_model_source(s.source);
  }
  requested_model_.reset();
  open_dims_ = s.dimensions;
  open_grid_ = c.session().settings().grid_size;
  open_zoom_ = c.session().settings().zoom_levels;
  const std::string ext = fs::path(c.space().default_export_name()).extension().string();
  if (save_path_.empty() || fs::path(save_path_).extension() != ext) {
    const fs::path folder =
        prefs_.save_folder.empty() ? default_save_folder() : fs::path(prefs_.save_folder);
    save_path_ = (folder / c.space().default_export_name()).string();
  }
}

void GalleryView::update_cells(GalleryController& c, float width, float height, float dpi) {
  sync_space(c);
  DesignSpace& space = c.space();
  const int n = c.session().settings().grid_size;
  layout_ = compute_layout(width, height, n, options_.cell_size);
  dpi = std::max(1.0f, dpi);
  dpi_ = dpi;
  cell_pixels_ = static_cast<int>(std::lround(dpi * layout_.cell));
  // What a person can tell apart depends on the size the cells are shown at.
  if (cell_pixels_ != sent_cell_pixels_) {
    c.queue(intent::SetCellPixels{cell_pixels_});
    sent_cell_pixels_ = cell_pixels_;
  }
  // Previews: two side by side in the side panel, at most 260 wide, in the space's aspect.
  const float aspect = std::max(0.2f, space.preview_aspect());
  float pw = std::min(260.0f, (layout_.side.w - 3 * kLayoutGap) / 2.0f);
  float ph = pw / aspect;
  const float max_h = std::max(80.0f, layout_.side.h * 0.42f);
  if (ph > max_h) {
    ph = max_h;
    pw = ph * aspect;
  }
  preview_w_ = static_cast<int>(pw);
  preview_h_ = static_cast<int>(ph);

  const auto& points = c.displayed_cells();
  if (cells_.size() != points.size()) cells_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells_[i].set_point(space, points[i].x, false);
    cells_[i].clamped = points[i].clamped;
  }
  const Session& s = c.session();
  if (slider_x_ && slider_x_->size() != space.dimensions()) slider_x_.reset();
  best_.set_point(space, slider_x_ ? *slider_x_ : s.current_best(), true);
  start_.set_point(space, s.start_point(), true);
  if (c.inspected() >= 0) {
    inspect_.set_point(space, s.history()[static_cast<std::size_t>(c.inspected())].chosen, true);
  }
  if (history_.size() != s.history().size()) history_.resize(s.history().size());
  for (std::size_t i = 0; i < history_.size(); ++i) {
    const Eigen::VectorXd& chosen = s.history()[i].chosen;
    if (history_[i].x.size() != chosen.size() || history_[i].x != chosen) {
      history_[i].x = chosen;
      history_[i].drawn = false;
    }
  }
}

void GalleryView::orbit(float dx, float dy) {
  camera_.orbit(dx, dy);
  active_preset_ = -1;
  ++camera_version_;
  camera_dragging_ = true;  // drawn as during a drag (build() clears it again)
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
  const bool fast = c.animating() || camera_dragging_;
  bool grid_drew = false;
  for (auto& cell : cells_) {
    grid_drew |= cell.draw(look, camera_version_, cell_pixels_, cell_pixels_, options_.samples,
                           fast, options_.animation_scale, options_.animation_samples > 0);
  }
  const int pwx = static_cast<int>(std::lround(dpi * pw));
  const int phx = static_cast<int>(std::lround(dpi * ph));
  (c.inspected() >= 0 ? inspect_ : best_).draw(look, camera_version_, pwx, phx, options_.samples);
  CellLook muted = look;
  muted.muted = true;
  start_.draw(muted, camera_version_, pwx, phx, options_.samples);
  const int tw = static_cast<int>(std::lround(dpi * 58.0f));
  const int th = static_cast<int>(std::lround(dpi * 58.0f / aspect));
  // A few new thumbnails a frame (a resumed long session has dozens), each drawn once, and
  // none in a frame that drew the grid: the grid comes first (launch, zoom, orbit).
  CellLook front = look;
  front.camera = space.uses_camera() ? &thumbnail_camera_ : nullptr;
  int budget = grid_drew ? 0 : 4;
  for (auto& h : history_) {
    if (h.drawn && h.fbo.width() == tw && h.fbo.height() == th) continue;
    if (budget-- == 0) break;
    CellView once;
    once.set_point(space, h.x, false);
    once.draw(front, 0, tw, th, options_.samples);
    h.fbo = std::move(once.fbo);
    h.drawn = true;
    ++thumbnail_draws_;
  }
}

void GalleryView::build(GalleryController& c, long frame) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("Sequential Gallery", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoBackground);  // glClear paints it, far cheaper
  ImGui::SetCursorScreenPos(ImVec2(layout_.toolbar.x, layout_.toolbar.y));
  draw_toolbar(c);
  ImGui::SetCursorScreenPos(ImVec2(layout_.messages.x, layout_.messages.y + 3));
  draw_messages(c);
  ImGui::SetCursorScreenPos(ImVec2(layout_.grid.x, layout_.grid.y));
  draw_grid(c, frame);
  ImGui::SetCursorScreenPos(ImVec2(layout_.side.x, layout_.side.y));
  ImGui::BeginChild("side", ImVec2(layout_.side.w, layout_.side.h), false);
  draw_side_panel(c);
  ImGui::EndChild();
  draw_modals(c);
  ImGui::End();
  poll_desktop_dialog(c);
}

void GalleryView::draw_toolbar(GalleryController& c) {
  ImGui::BeginDisabled(!c.can_undo_click());
  if (ImGui::Button("Undo click")) c.queue(intent::UndoClick{});
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Take back the last click (Backspace / Ctrl+Z)");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!c.can_undo_plane());
  if (ImGui::Button("Undo plane")) c.queue(intent::UndoPlane{});
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Go back to the start of the last finished plane");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!c.can_redo());
  if (ImGui::Button("Redo")) c.queue(intent::Redo{});
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Redo what Undo took back (Ctrl+Y / Ctrl+Shift+Z)");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(c.busy() || !c.has_progress());
  if (ImGui::Button("Start over")) confirm_start_over_ = true;
  ImGui::EndDisabled();
  if (c.space().uses_camera()) {
    ImGui::SameLine();
    ImGui::TextDisabled("|");
    ImGui::SameLine();
    ImGui::TextUnformatted("View:");
    const char* labels[] = {"Front", "Side", "3/4"};
    for (int i = 0; i < 3; ++i) {
      ImGui::SameLine();
      if (ImGui::RadioButton(labels[i], active_preset_ == i)) set_preset(i);
    }
  }
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  const auto& s = c.session().settings();
  ImGui::Text("Plane %d   click %d of %d", c.session().planes_done() + 1,
              std::min(c.session().clicks_on_plane() + (c.busy() ? 0 : 1), s.zoom_levels),
              s.zoom_levels);
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  ImGui::Text("%s: %s", c.space().uses_camera() ? "Model" : "Photo",
              c.space().source_label().c_str());
  note_widget("toolbar:model");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.space().description().c_str());
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

void GalleryView::draw_grid(GalleryController& c, long frame) {
  const int n = c.session().settings().grid_size;
  const float shown = layout_.cell;
  const float gap = layout_.gap;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 origin(layout_.grid.x, layout_.grid.y);
  const ImGuiIO& io = ImGui::GetIO();
  hovered_ = -1;
  const bool busy = c.busy();
  // The second press of a double-click is never a zoom step of its own.
  if (io.MouseClicked[0]) second_of_double_ = io.MouseDoubleClicked[0];
  camera_dragging_ = false;
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const int index = row * n + col;
      const ImVec2 p0(origin.x + static_cast<float>(col) * (shown + gap),
                      origin.y + static_cast<float>(row) * (shown + gap));
      const ImVec2 p1(p0.x + shown, p0.y + shown);
      ImGui::SetCursorScreenPos(p0);
      ImGui::PushID(index);
      const bool pressed = ImGui::InvisibleButton("cell", ImVec2(shown, shown));
      const bool hovered = ImGui::IsItemHovered();
      const bool dragging = ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left);
      ImGui::PopID();
      if (dragging) camera_dragging_ = true;
      if (dragging && c.space().uses_camera() &&
          (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
        active_preset_ = -1;  // a free orbit
        ++camera_version_;
      }
      const float drag_threshold = io.MouseDragThreshold * io.MouseDragThreshold;
      if (pressed && io.MouseDragMaxDistanceSqr[0] < drag_threshold) {
        if (second_of_double_) {
          second_of_double_ = false;
        } else {
          c.queue(intent::ClickCell{col, row});
        }
      }
      if (options_.report_layout && frame == 3) {
        std::cout << "[layout] cell " << index + 1 << " " << p0.x << " " << p0.y << " " << shown
                  << std::endl;
      }
      if (static_cast<std::size_t>(index) < cells_.size()) {
        const CellView& view = cells_[static_cast<std::size_t>(index)];
        if (view.fbo.texture() != 0) {
          const auto uv = view.uv();
          // Cells are opaque: drawing them without blending saves a software rasterizer
          // reading back every cell's pixels every frame.
          dl->AddCallback(&disable_blending, nullptr);
          dl->AddImage(texture_id(view.fbo.texture()), p0, p1, ImVec2(uv[0], uv[1]),
                       ImVec2(uv[2], uv[3]));
          dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
        }
      }
      if (hovered && !busy) {
        hovered_ = index;
        dl->AddRectFilled(p0, p1, IM_COL32(255, 255, 255, 22));
        dl->AddRect(p0, p1, IM_COL32(255, 190, 60, 255), 0.0f, 0, 4.0f);
      } else {
        dl->AddRect(p0, p1, IM_COL32(40, 40, 48, 255), 0.0f, 0, 1.0f);
      }
      const std::string label = cell_label(index, n);
      const ImVec2 ls = ImGui::CalcTextSize(label.c_str());
      dl->AddRectFilled(ImVec2(p0.x + 4, p0.y + 4), ImVec2(p0.x + 12 + ls.x, p0.y + 6 + ls.y),
                        IM_COL32(20, 22, 28, 150), 3.0f);
      dl->AddText(ImVec2(p0.x + 8, p0.y + 5), IM_COL32(240, 240, 245, 255), label.c_str());
      if (static_cast<std::size_t>(index) < cells_.size() &&
          cells_[static_cast<std::size_t>(index)].clamped && shown >= 90.0f) {
        const char* edge = "edge of the range";
        const ImVec2 es = ImGui::CalcTextSize(edge);
        dl->AddRectFilled(ImVec2(p0.x + 4, p1.y - 8 - es.y), ImVec2(p0.x + 12 + es.x, p1.y - 4),
                          IM_COL32(20, 22, 28, 150), 3.0f);
        dl->AddText(ImVec2(p0.x + 8, p1.y - 6 - es.y), IM_COL32(255, 180, 90, 255), edge);
      }
    }
  }
  const float total = static_cast<float>(n) * shown + static_cast<float>(n - 1) * gap;
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(ImVec2(total, total));
  if (busy) {
    const ImVec2 m(origin.x + total * 0.5f, origin.y + total * 0.5f);
    dl->AddRectFilled(ImVec2(m.x - 170, m.y - 46), ImVec2(m.x + 170, m.y + 46),
                      IM_COL32(20, 22, 28, 200), 8.0f);
    const float t = static_cast<float>(ImGui::GetTime()) * 6.0f;
    dl->PathArcTo(ImVec2(m.x - 130, m.y), 18.0f, t, t + 4.2f, 32);
    dl->PathStroke(IM_COL32(80, 160, 255, 255), 0, 4.5f);
    dl->AddText(ImVec2(m.x - 100, m.y - 8), IM_COL32(235, 235, 240, 255),
                "Computing the next plane...");
  }
  if (hovered_ >= 0 && !c.animating() && !busy) {
    const int col = hovered_ % n, row = hovered_ / n;
    const ImVec2 cell_min(origin.x + static_cast<float>(col) * (shown + gap),
                          origin.y + static_cast<float>(row) * (shown + gap));
    draw_hover_details(c, LayoutRect{cell_min.x, cell_min.y, shown, shown}, origin.x + total * 0.5f,
                       origin.y + total * 0.5f);
  }
}

void GalleryView::draw_hover_details(const GalleryController& c, const LayoutRect& cell,
                                     float centre_x, float centre_y) {
  const ImVec2 cell_min(cell.x, cell.y), cell_max(cell.x + cell.w, cell.y + cell.h);
  const auto& points = c.displayed_cells();
  if (hovered_ >= static_cast<int>(points.size()) || !best_.prepared) return;
  const Eigen::VectorXd& x = points[static_cast<std::size_t>(hovered_)].x;
  if (!hover_details_ || hover_details_->x.size() != x.size() ||
      (hover_details_->x - x).cwiseAbs().maxCoeff() > 1e-12) {
    hover_details_ = c.space().prepare(x, true);
  }
  // A tooltip over the grid covered the very cells being compared; the measurements table's
  // "hovered" column has the numbers. Inside the cell, one line says what differs most.
  if (!ImGui::GetIO().KeyShift) {
    std::string summary = c.space().cell_summary(*hover_details_, *best_.prepared);
    if (summary.empty()) return;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float width = cell_max.x - cell_min.x - 8.0f;
    ImVec2 size = ImGui::CalcTextSize(summary.c_str(), nullptr, false, width);
    // A small cell (a 5x5 photo grid) keeps most of its picture: the first item only, and
    // nothing when even that would cover a third of it.
    if (size.y > 0.3f * cell.h) {
      summary = summary.substr(0, summary.find(", "));
      size = ImGui::CalcTextSize(summary.c_str(), nullptr, false, width);
      if (size.y > 0.3f * cell.h) return;
    }
    // Above the cell's "edge of the range" label when it has one.
    const float lift = points[static_cast<std::size_t>(hovered_)].clamped ? size.y + 8.0f : 0.0f;
    const ImVec2 p(cell_min.x + 4.0f, cell_max.y - 6.0f - size.y - lift);
    dl->AddRectFilled(ImVec2(p.x, p.y - 2.0f), ImVec2(p.x + size.x + 8.0f, p.y + size.y + 2.0f),
                      IM_COL32(20, 22, 28, 190), 3.0f);
    dl->AddText(nullptr, 0.0f, ImVec2(p.x + 4.0f, p.y), IM_COL32(255, 220, 150, 255),
                summary.c_str(), nullptr, width);
    return;
  }
  // Shift: the whole comparison, opening away from the grid's edges.
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const ImVec2 pivot(mouse.x > centre_x ? 1.0f : 0.0f, mouse.y > centre_y ? 1.0f : 0.0f);
  const float offset = 18.0f;
  ImGui::SetNextWindowPos(ImVec2(mouse.x + (pivot.x > 0 ? -offset : offset),
                                 mouse.y + (pivot.y > 0 ? -offset : offset)),
                          ImGuiCond_Always, pivot);
  ImGui::BeginTooltip();
  ImGui::Text("Cell %s", cell_label(hovered_, c.session().settings().grid_size).c_str());
  c.space().draw_inspector(*hover_details_, "this cell", best_.prepared.get(), "current best");
  if (points[static_cast<std::size_t>(hovered_)].clamped) {
    ImGui::TextDisabled("Some values of this cell are at the edge of their range.");
  }
  ImGui::EndTooltip();
}

void GalleryView::draw_side_panel(GalleryController& c) {
  const bool inspecting = c.inspected() >= 0;
  const CellView& shown = inspecting ? inspect_ : best_;
  char title[64];
  if (inspecting) {
    std::snprintf(title, sizeof title, "Plane %d choice", c.inspected() + 1);
  } else if (slider_x_) {
    std::snprintf(title, sizeof title, "Sliders (not chosen yet)");
  } else {
    std::snprintf(title, sizeof title, "Current best");
  }
  const ImVec2 size(static_cast<float>(preview_w_), static_cast<float>(preview_h_));
  ImGui::BeginGroup();
  ImGui::TextUnformatted(title);
  if (shown.fbo.texture() != 0) {
    ImGui::Image(texture_id(shown.fbo.texture()), size, ImVec2(0, 1), ImVec2(1, 0));
  } else {
    ImGui::Dummy(size);
  }
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  // The body the search began with, as it was (not projected onto any holds in force): holds
  // shape what the grid shows from now on; the start is the reference the user compares with
  // (the measurements panel's "start" column reads its own values, e.g. the height before it
  // was held at another).
  ImGui::TextUnformatted("Started from");
  if (start_.fbo.texture() != 0) {
    ImGui::Image(texture_id(start_.fbo.texture()), size, ImVec2(0, 1), ImVec2(1, 0));
  } else {
    ImGui::Dummy(size);
  }
  ImGui::EndGroup();
  if (inspecting && ImGui::Button("Back to current best")) c.queue(intent::Inspect{-1});
  if (!c.space().measurement_names().empty()) {
    // Issue 13: measurements of the current best, the start and the hovered cell, holds and
    // targets. The panel only asks; the controller applies between frames.
    if (ImGui::CollapsingHeader("Measurements", ImGuiTreeNodeFlags_DefaultOpen)) {
      const PreparedCell* hovered = hovered_ >= 0 ? hover_details_.get() : nullptr;
      // Typed targets and the units survive a relaunch (ui.json).
      const auto names = c.space().measurement_names();
      if (measurement_panel_.target_text.size() != names.size()) {
        measurement_panel_.target_text.assign(names.size(), "");
        for (std::size_t i = 0; i < names.size(); ++i) {
          const auto it = prefs_.typed_targets.find(names[i]);
          if (it != prefs_.typed_targets.end()) measurement_panel_.target_text[i] = it->second;
        }
        measurement_panel_.imperial = prefs_.imperial;
      }
      const auto request = c.space().draw_measurement_panel(
          shown.prepared.get(), start_.prepared.get(), hovered, c.holds(), measurement_panel_);
      for (std::size_t i = 0; i < names.size() && i < measurement_panel_.target_text.size(); ++i) {
        if (measurement_panel_.target_text[i].empty()) {
          prefs_.typed_targets.erase(names[i]);
        } else {
          prefs_.typed_targets[names[i]] = measurement_panel_.target_text[i];
        }
      }
      prefs_.imperial = measurement_panel_.imperial;
      if (request.holds) c.queue(intent::SetHolds{*request.holds});
      if (request.targets) c.queue(intent::GoToTargets{*request.targets});
      if (!c.holds().empty()) {
        ImGui::TextColored(ImVec4(0.55f, 0.8f, 1.0f, 1.0f), "Held in every cell: %s",
                           c.holds_description().c_str());
      }
    }
  } else if (shown.prepared && start_.prepared) {
    c.space().draw_inspector(*shown.prepared, inspecting ? "chosen" : "current",
                             start_.prepared.get(), "start");
  }
  draw_sliders(c);
  draw_history(c);
  draw_save(c);
  draw_open(c);
  ImGui::Separator();
  ImGui::TextDisabled("Design space: %s", c.space().description().c_str());
  ImGui::TextDisabled("Session: %s%s", c.session_path().string().c_str(),
                      c.autosave_enabled() ? "" : " (autosave OFF)");
  ImGui::TextDisabled(
      "Keys: %s pick a cell, Backspace/Ctrl+Z undo, Ctrl+Y redo, Ctrl+S save, "
      "Ctrl+Q quit; hold Shift over a cell for all its measurements",
      c.session().settings().grid_size == 3 ? "1-9" : "A-Y");
  if (c.space().uses_camera()) ImGui::TextDisabled("Drag a cell to orbit all bodies");
}

// The paper's user-study request: direct control for experts. The sliders start at the
// current best; the preview follows them; "Use this" submits the point as preferred over the
// previous best (it becomes the current best).
void GalleryView::draw_sliders(GalleryController& c) {
  if (!ImGui::CollapsingHeader("Expert sliders")) {
    sliders_panel_ = false;
    return;
  }
  sliders_panel_ = true;
  const Eigen::VectorXd best = c.session().current_best();
  Eigen::VectorXd x = slider_x_ ? *slider_x_ : best;
  bool changed = false;
  const float label_width = std::min(220.0f, ImGui::GetContentRegionAvail().x * 0.45f);
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
  if (changed) slider_x_ = x;
  if (!c.holds().empty()) {
    // The sliders move every component freely; what is held is restored when the point is used.
    ImGui::TextWrapped("Held: %s. Use this moves the sliders' body onto the holds.",
                       c.holds_description().c_str());
  }
  ImGui::BeginDisabled(!slider_x_ || c.busy());
  if (ImGui::Button("Use this")) {
    c.queue(intent::UsePoint{*slider_x_});
    slider_x_.reset();
  }
  ImGui::SameLine();
  if (ImGui::Button("Back to the current best")) slider_x_.reset();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Discard the slider changes");
  }
}

void GalleryView::draw_history(GalleryController& c) {
  ImGui::SetNextItemOpen(prefs_.history_panel, ImGuiCond_Once);
  prefs_.history_panel = ImGui::CollapsingHeader("History");
  if (!prefs_.history_panel) return;
  ImGui::Text("%d finished plane%s (click one to inspect it)", c.session().planes_done(),
              c.session().planes_done() == 1 ? "" : "s");
  const float aspect = std::max(0.2f, c.space().preview_aspect());
  const ImVec2 thumb(58.0f, 58.0f / aspect);
  ImGui::BeginChild("history", ImVec2(0, thumb.y + 40), true, ImGuiWindowFlags_HorizontalScrollbar);
  for (std::size_t i = 0; i < history_.size(); ++i) {
    if (i > 0) ImGui::SameLine();
    ImGui::PushID(static_cast<int>(i));
    ImGui::BeginGroup();
    const bool selected = c.inspected() == static_cast<int>(i);
    if (selected) ImGui::PushStyleColor(ImGuiCol_Button, IM_COL32(255, 170, 40, 255));
    if (ImGui::ImageButton(texture_id(history_[i].fbo.texture()), thumb, ImVec2(0, 1), ImVec2(1, 0),
                           2)) {
      c.queue(intent::Inspect{selected ? -1 : static_cast<int>(i)});
    }
    if (selected) ImGui::PopStyleColor();
    ImGui::Text("#%zu", i + 1);
    ImGui::EndGroup();
    ImGui::PopID();
  }
  if (history_.empty()) ImGui::TextDisabled("the choice of every finished plane appears here");
  ImGui::EndChild();
}

void GalleryView::draw_save(GalleryController& c) {
  ImGui::SetNextItemOpen(prefs_.save_panel, ImGuiCond_Once);
  prefs_.save_panel = ImGui::CollapsingHeader("Save##panel");
  if (!prefs_.save_panel) return;
  ImGui::TextWrapped("Save the shown %s (%s)", c.inspected() >= 0 ? "choice" : "current best",
                     c.space().export_hint().c_str());
  ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 150.0f));
  ImGui::InputText("##savepath", &save_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save##quick")) quick_save(c);
  ImGui::SameLine();
  if (ImGui::Button("Save as...")) open_save_dialog(c);
  // Where Save writes, in full: a relative name is relative to the folder the program was
  // started from, which the field alone does not say.
  std::error_code ec;
  const fs::path target = save_path_.empty() ? fs::path() : fs::absolute(save_path_, ec);
  if (!target.empty()) ImGui::TextDisabled("saves to %s", target.string().c_str());
}

void GalleryView::draw_open(GalleryController& c) {
  ImGui::SetNextItemOpen(prefs_.open_panel, ImGuiCond_Once);
  prefs_.open_panel = ImGui::CollapsingHeader("New search: another model, image or grid");
  note_widget("panel:new-search");
  if (!prefs_.open_panel) return;
  ImGui::TextUnformatted("Design:");
  ImGui::SameLine();
  if (ImGui::RadioButton("body shape", open_kind_ == "body")) {
    if (open_kind_ != "body") open_dims_ = 10, open_grid_ = 3;
    open_kind_ = "body";
  }
  ImGui::SameLine();
  if (ImGui::RadioButton("photo colours", open_kind_ == "photo")) {
    if (open_kind_ != "photo") open_source_ = open_photo_file_, open_dims_ = 12, open_grid_ = 3;
    open_kind_ = "photo";
  }
  if (open_kind_ == "body") {
    draw_model_picker();
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt("components", &open_dims_);
    open_dims_ = std::clamp(open_dims_, 1, sps::kMaxSearchDims);
  } else {
    ImGui::TextUnformatted("Photo (.png/.jpg; empty = the built-in landscape; or drop one here)");
    ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 90.0f));
    ImGui::InputTextWithHint("##source", "built-in landscape", &open_source_);
    note_widget("photo:file");
    ImGui::SameLine();
    if (ImGui::Button("Browse...##photo")) open_image_dialog();
    note_widget("photo:browse");
    std::error_code ec;
    if (!open_source_.empty() && !fs::exists(open_source_, ec)) {
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "No such file");
    }
  }
  ImGui::TextUnformatted("Grid");
  ImGui::SameLine();
  ImGui::RadioButton("3x3", &open_grid_, 3);
  ImGui::SameLine();
  ImGui::RadioButton("5x5", &open_grid_, 5);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::InputInt("clicks/plane", &open_zoom_);
  open_zoom_ = std::clamp(open_zoom_, 1, 8);
  std::error_code exists_ec;
  const bool no_file =
      (open_kind_ == "body" && open_model_ == "file" && open_model_file_.empty()) ||
      (open_kind_ == "photo" && !open_source_.empty() && !fs::exists(open_source_, exists_ec));
  ImGui::BeginDisabled(c.busy() || no_file);
  if (ImGui::Button("Open / apply (starts a new search)")) start_new_search(c);
  note_widget("new-search");
  ImGui::EndDisabled();
}

// Neutral / Female / Male / File...: the built-in models by name, or a model file chosen with
// the file dialog (or typed, or dropped on the window).
void GalleryView::draw_model_picker() {
  ImGui::TextUnformatted("Body model:");
  for (const std::string& name : spaces::builtin_body_models()) {
    std::string label = name;
    if (!label.empty())
      label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
    ImGui::SameLine();
    if (ImGui::RadioButton(label.c_str(), open_model_ == name)) choose_model(name);
    note_widget("model:" + name);
  }
  ImGui::SameLine();
  if (ImGui::RadioButton("File...", open_model_ == "file")) choose_model("file");
  note_widget("model:file");
  if (open_model_ != "file") return;
  ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 90.0f));
  ImGui::InputTextWithHint("##modelfile", "model .npz", &open_model_file_);
  ImGui::SameLine();
  if (ImGui::Button("Browse...")) open_model_dialog();
  note_widget("model:browse");
  std::error_code ec;
  if (open_model_file_.empty()) {
    ImGui::TextDisabled("Choose an SMPL-layout .npz (an SMPL .pkl: convert it first, see README)");
  } else if (!fs::exists(open_model_file_, ec)) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "No such file");
  }
}

void GalleryView::select_model_source(const std::string& source) {
  if (source.empty()) {
    open_model_ = "neutral";
  } else if (is_builtin_body_model(source)) {
    open_model_ = source;
  } else {
    open_model_ = "file";
    open_model_file_ = source;
  }
}

void GalleryView::choose_model(const std::string& choice) {
  if (choice == "file") {
    open_model_ = "file";
    if (open_model_file_.empty()) open_model_dialog();
    return;
  }
  if (is_builtin_body_model(choice)) open_model_ = choice;
}

void GalleryView::set_model_file(const std::string& path) {
  open_model_ = "file";
  open_model_file_ = path;
}

void GalleryView::start_new_search(GalleryController& c) {
  SpaceSettings space{open_kind_, open_source_, open_kind_ == "body" ? open_dims_ : 12};
  if (open_kind_ == "photo" && !open_source_.empty()) {
    // As for a model file: the session keeps the picture wherever the program starts next.
    std::error_code ec;
    const fs::path absolute = fs::absolute(open_source_, ec);
    if (!ec) space.source = absolute.lexically_normal().string();
  }
  if (open_kind_ == "body") {
    if (open_model_ == "file") {
      if (open_model_file_.empty()) return;
      // The session and the prefs keep the file wherever the program is started from next.
      std::error_code ec;
      const fs::path absolute = fs::absolute(open_model_file_, ec);
      space.source = ec ? open_model_file_ : absolute.lexically_normal().string();
    } else {
      space.source = open_model_;
    }
    requested_model_ = space.source;
  }
  const intent::Open o{space, open_grid_, open_zoom_};
  if (c.has_progress()) {
    confirm_open_ = o;  // ask first: a search is work
  } else {
    c.queue(o);
  }
}

std::optional<LayoutRect> GalleryView::widget(const std::string& name) const {
  const auto it = widgets_.find(name);
  if (it == widgets_.end()) return std::nullopt;
  return it->second;
}

// Remembers where the last item was drawn (and prints it for scripted tests when it moves).
void GalleryView::note_widget(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const LayoutRect r{a.x, a.y, b.x - a.x, b.y - a.y};
  LayoutRect& known = widgets_[name];
  const bool moved = known.x != r.x || known.y != r.y || known.w != r.w || known.h != r.h;
  known = r;
  if (moved && options_.report_layout) {
    std::cout << "[layout] widget " << name << " " << r.x << " " << r.y << " " << r.w << " " << r.h
              << std::endl;
  }
}

void GalleryView::draw_modals(GalleryController& c) {
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
                    instead.c_str(), c.resume_candidate()->settings().space.c_str());
      }
      if (elsewhere) {
        ImGui::TextUnformatted(
            "This window saves nothing, so the other one loses no clicks. Close the other window "
            "to continue the search here.");
      }
      const std::string resume_label =
          elsewhere ? "View read-only"
                    : (instead.empty()
                           ? "Resume"
                           : "Resume the " + c.resume_candidate()->settings().space + " search");
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
  if (confirm_open_) {
    if (!ImGui::IsPopupOpen("Start a new search?")) ImGui::OpenPopup("Start a new search?");
    if (ImGui::BeginPopupModal("Start a new search?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("The current search has %d finished plane(s) and %d click(s).",
                  c.session().planes_done(), c.session().clicks_on_plane());
      ImGui::Text("A new search %s replaces it; its session file is kept as %s.previous.",
                  what_is_opened(confirm_open_->space).c_str(),
                  c.session_path().filename().string().c_str());
      if (ImGui::Button("Start the new search", ImVec2(200, 0))) {
        c.queue(*confirm_open_);
        confirm_open_.reset();
        ImGui::CloseCurrentPopup();
      }
      note_widget("confirm:start");
      ImGui::SameLine();
      if (ImGui::Button("Keep searching", ImVec2(160, 0))) {
        confirm_open_.reset();
        requested_model_.reset();
        ImGui::CloseCurrentPopup();
      }
      note_widget("confirm:keep");
      ImGui::EndPopup();
    }
  }
  if (confirm_overwrite_) {
    if (!ImGui::IsPopupOpen("Replace file?")) ImGui::OpenPopup("Replace file?");
    if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("%s already exists.", confirm_overwrite_->string().c_str());
      if (ImGui::Button("Replace it", ImVec2(140, 0))) {
        c.queue(intent::Export{*confirm_overwrite_});
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
  }
  if (browser_open_) draw_file_browser();
  if (browser_result_) {
    const fs::path chosen = *browser_result_;
    browser_result_.reset();
    file_chosen(c, chosen);
  }
}

void GalleryView::draw_file_browser() {
  const bool saving = dialog_purpose_ == DialogPurpose::kSave;
  const bool image = dialog_purpose_ == DialogPurpose::kOpenImage;
  const char* title = saving ? "Save as" : image ? "Open a photo" : "Open a body model";
  if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title, nullptr)) return;
  ImGui::TextUnformatted("Folder:");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##dir", &browser_dir_);
  ImGui::BeginChild("entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2.2f), true);
  std::error_code ec;
  const fs::path dir = browser_dir_.empty() ? fs::current_path(ec) : fs::path(browser_dir_);
  if (dir.has_parent_path() && dir != dir.root_path() && ImGui::Selectable("../")) {
    browser_dir_ = dir.parent_path().string();
  }
  std::vector<fs::directory_entry> entries;
  for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().rfind('.', 0) == 0) continue;
    std::error_code e1;
    // Opening a model: folders and model files only (.pkl too, to say how to convert it);
    // a photo: folders and pictures.
    const std::string ext = lower_extension(it->path());
    const bool wanted = image ? (ext == ".png" || ext == ".jpg" || ext == ".jpeg")
                              : (ext == ".npz" || ext == ".pkl");
    if (!saving && !it->is_directory(e1) && !wanted) continue;
    entries.push_back(*it);
  }
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    std::error_code e1, e2;
    const bool da = a.is_directory(e1), db = b.is_directory(e2);
    return da != db ? da : a.path().filename() < b.path().filename();
  });
  if (ec) ImGui::TextDisabled("cannot list %s: %s", dir.string().c_str(), ec.message().c_str());
  for (const auto& e : entries) {
    std::error_code e1;
    const bool is_dir = e.is_directory(e1);
    const std::string name = e.path().filename().string() + (is_dir ? "/" : "");
    if (ImGui::Selectable(name.c_str())) {
      if (is_dir) {
        browser_dir_ = e.path().string();
      } else {
        browser_name_ = e.path().filename().string();
      }
    }
  }
  ImGui::EndChild();
  ImGui::TextUnformatted("File name:");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##name", &browser_name_);
  note_widget("browser:name");
  if (ImGui::Button(saving ? "Save" : "Open", ImVec2(120, 0)) && !browser_name_.empty()) {
    browser_result_ = dir / browser_name_;
    browser_open_ = false;
    ImGui::CloseCurrentPopup();
  }
  note_widget("browser:ok");
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0))) {
    browser_open_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void GalleryView::open_save_dialog(GalleryController& c) {
  if (desktop_dialog_.valid() || browser_open_) return;  // one is open already
  dialog_purpose_ = DialogPurpose::kSave;
  const fs::path current =
      save_path_.empty() ? fs::path(c.space().default_export_name()) : fs::path(save_path_);
  std::error_code ec;
  const fs::path folder = current.has_parent_path() ? current.parent_path() : fs::current_path(ec);
  open_file_dialog(folder, current.filename().string());
}

void GalleryView::open_model_dialog() {
  if (desktop_dialog_.valid() || browser_open_) return;
  dialog_purpose_ = DialogPurpose::kOpenModel;
  const fs::path current(open_model_file_);
  std::error_code ec;
  const fs::path folder = current.has_parent_path() ? current.parent_path() : fs::current_path(ec);
  open_file_dialog(folder, current.filename().string());
}

void GalleryView::open_image_dialog() {
  if (desktop_dialog_.valid() || browser_open_) return;
  dialog_purpose_ = DialogPurpose::kOpenImage;
  const fs::path current(open_source_.empty() ? open_photo_file_ : open_source_);
  std::error_code ec;
  const fs::path folder = current.has_parent_path() ? current.parent_path() : fs::current_path(ec);
  open_file_dialog(folder, current.filename().string());
}

// The desktop's dialog (zenity, kdialog) when there is one and it is wanted, else the in-app
// browser; for saving, opening a body model or opening a photo, per dialog_purpose_.
void GalleryView::open_file_dialog(const fs::path& folder, const std::string& name) {
  const bool saving = dialog_purpose_ == DialogPurpose::kSave;
  if (options_.file_dialog != "builtin") {
    const std::string start = shell_quote((folder / name).string());
    std::string command;
    const bool image = dialog_purpose_ == DialogPurpose::kOpenImage;
    if (const std::string zenity = find_program("zenity"); !zenity.empty()) {
      command = shell_quote(zenity) + " --file-selection " +
                (saving  ? std::string("--save --title='Save'")
                 : image ? std::string("--title='Choose a photo' --file-filter='Photos (.png, "
                                       ".jpg) | *.png *.jpg *.jpeg *.PNG *.JPG *.JPEG' "
                                       "--file-filter='All files | *'")
                         : std::string("--title='Choose a body model' --file-filter='Body models "
                                       "(.npz) | *.npz' --file-filter='All files | *'")) +
                " --filename=" + start + " 2>/dev/null";
    } else if (const std::string kdialog = find_program("kdialog"); !kdialog.empty()) {
      command = shell_quote(kdialog) +
                (saving  ? " --getsavefilename " + start
                 : image ? " --getopenfilename " + start + " '*.png *.jpg *.jpeg|Photos'"
                         : " --getopenfilename " + start + " '*.npz|Body models (.npz)'") +
                " 2>/dev/null";
    }
    if (!command.empty()) {
      desktop_dialog_ = std::async(std::launch::async, [command] { return run_dialog(command); });
      return;
    }
  }
  std::error_code ec;
  browser_dir_ = fs::absolute(folder, ec).string();
  browser_name_ = name;
  browser_open_ = true;
}

void GalleryView::file_chosen(GalleryController& c, const fs::path& path) {
  if (dialog_purpose_ == DialogPurpose::kSave) {
    request_export(c, path);
  } else if (dialog_purpose_ == DialogPurpose::kOpenImage) {
    open_source_ = path.string();
  } else {
    set_model_file(path.string());
  }
}

void GalleryView::poll_desktop_dialog(GalleryController& c) {
  if (!desktop_dialog_.valid() ||
      desktop_dialog_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return;
  }
  if (const auto path = desktop_dialog_.get()) file_chosen(c, *path);
}

void GalleryView::request_export(GalleryController& c, const fs::path& path) {
  save_path_ = path.string();
  std::error_code ec;
  prefs_.save_folder = fs::absolute(path, ec).parent_path().string();
  prefs_.save_name = path.filename().string();
  // Ask before replacing a file, except the one this session just saved (saving again).
  if (fs::exists(path, ec) && fs::absolute(path, ec) != fs::absolute(c.last_export(), ec)) {
    confirm_overwrite_ = path;
    std::cout << "[gallery] asking before replacing " << path.string() << std::endl;
    return;
  }
  c.queue(intent::Export{path});
}

void GalleryView::quick_save(GalleryController& c) {
  if (save_path_.empty()) {
    open_save_dialog(c);
    return;
  }
  request_export(c, save_path_);
}

void GalleryView::open_dropped(GalleryController& c, const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  const bool image = ext == ".png" || ext == ".PNG" || ext == ".jpg" || ext == ".jpeg" ||
                     ext == ".JPG" || ext == ".JPEG";
  open_kind_ = image ? "photo" : "body";
  prefs_.open_panel = true;
  if (image) {
    open_source_ = path;
    open_dims_ = 12;
    open_grid_ = 3;
  } else {
    set_model_file(path);
    open_grid_ = 3;
  }
  start_new_search(c);
}

void GalleryView::press_cell(GalleryController& c, int index) {
  const int n = c.session().settings().grid_size;
  if (index < 0 || index >= n * n) return;
  c.queue(intent::ClickCell{index % n, index / n});
}

}  // namespace app
