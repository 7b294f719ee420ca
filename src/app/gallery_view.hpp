// The gallery's window content, as panels (Dear ImGui): the toolbar and messages, the grid,
// and a side panel with the previews above tabs for measurements, sliders, history, save and
// new search. Panels read the controller's state and queue intents; they change nothing
// themselves. The view also owns what is drawn on the GPU for the frame (grid cells, previews),
// rendered before the UI frame starts, and the camera.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cell_view.hpp"
#include "app/file_dialogs.hpp"
#include "app/gallery_controller.hpp"
#include "app/gallery_layout.hpp"
#include "app/grid_panel.hpp"
#include "app/history_panel.hpp"
#include "app/measurements_panel.hpp"
#include "app/new_search_panel.hpp"
#include "app/panel_context.hpp"
#include "app/save_panel.hpp"
#include "app/sliders_panel.hpp"
#include "app/space_catalogue.hpp"
#include "app/ui_prefs.hpp"
#include "render/camera.hpp"

namespace app {

struct ViewOptions {
  int cell_size = 0;             // cell edge in pixels; 0 = fit the window
  int samples = 4;               // MSAA samples per cell
  int animation_samples = 0;     // > 0: keep MSAA while the grid animates
  float animation_scale = 1.0f;  // cell resolution factor while animating
  std::string save_path;         // "Save" default (empty: the remembered or the space's name)
  bool report_layout = false;    // print the grid cells' window rectangles (scripted tests)
  // File dialogs: "auto" (the desktop's zenity or kdialog when installed, else the in-app
  // browser), "builtin" (always the in-app browser).
  std::string file_dialog = "auto";
};

// The side panel's tabs, in order, by the names ui.json keeps ("measurements", ...).
const std::vector<std::string>& side_panel_tabs();

class GalleryView {
 public:
  GalleryView(ViewOptions options, UiPrefs prefs, const SpaceCatalogue& catalogue);
  ~GalleryView();

  // Before the UI frame, after the controller applied its intents: lays the window out and
  // prepares (CPU) and uploads every cell whose point changed. `dpi` = framebuffer / window
  // pixels.
  void update_cells(GalleryController& c, float width, float height, float dpi);
  // Then renders every cell whose content, size or camera changed into its framebuffer.
  void draw_cells(GalleryController& c);
  // Builds the ImGui panels for this frame; input becomes intents queued on `c`.
  void build(GalleryController& c, long frame);

  // Keyboard shortcuts, translated by the window: a cell by its label (0-based index), save.
  void press_cell(GalleryController& c, int index);
  void quick_save(GalleryController& c);
  // A file dropped on the window: the model or image for a new search (asks first if the
  // current search has progress).
  void open_dropped(GalleryController& c, const std::string& path);
  // The file Save is asking before replacing, if it is asking.
  const std::optional<std::filesystem::path>& overwrite_question() const {
    return save_.question();
  }
  // How many history thumbnails were drawn so far (each once: tests check that orbiting the
  // grid draws none).
  long thumbnail_draws() const { return history_.draws(); }
  // Switches the view preset (0 front, 1 side, 2 three-quarter), as its toolbar button does.
  void choose_view(int index) { set_preset(index); }
  // Turns the shared camera as dragging across a cell does (bench-gui's orbit frames).
  void orbit(float dx, float dy);
  // A desktop file dialog is open (the window keeps polling).
  bool waiting_for_dialog() const { return dialogs_.waiting_for_desktop(); }

  // The New-search panel's source picker for the shown kind (a body search: "neutral",
  // "female", "male" or "file"). What the panel's buttons call; tests call them too.
  std::string model_choice() const { return new_search_.source_choice(); }
  void choose_model(const std::string& choice) { new_search_.choose_source(choice); }
  void set_model_file(const std::string& path) { new_search_.use_source_file(path); }
  // Where a named widget of the last frame was, in window pixels ("model:female",
  // "new-search", "tab:new-search", "confirm:start"), for scripted tests.
  std::optional<LayoutRect> widget(const std::string& name) const { return widgets_.find(name); }

  const GalleryLayout& layout() const { return layout_; }
  int cell_pixels() const { return cell_pixels_; }
  int hovered_cell() const { return grid_.hovered(); }
  bool text_input_active() const;
  const UiPrefs& prefs() const { return prefs_; }
  std::string save_path() const { return save_.path(); }
  // Drops every GL object (before the context goes).
  void release_gl();
  // Label of cell `index` on an n x n grid: 1-9 on 3x3, A-Y on 5x5 (also its key).
  static std::string cell_label(int index, int n) { return app::cell_label(index, n); }

 private:
  PanelContext context(GalleryController& c);
  void sync_space(GalleryController& c);
  void draw_toolbar(GalleryController& c);
  void draw_messages(const GalleryController& c);
  void draw_side_panel(PanelContext& ctx);
  void draw_tabs(PanelContext& ctx);
  void draw_questions(PanelContext& ctx);
  void take_file_answer(PanelContext& ctx);
  void set_preset(int index);

  ViewOptions options_;
  UiPrefs prefs_;
  const SpaceCatalogue& catalogue_;
  GalleryLayout layout_;
  int space_generation_ = -1;
  FileDialogs dialogs_;
  WidgetNotes widgets_;

  render::Camera camera_;
  int active_preset_ = 0;  // -1 after a free orbit
  int camera_version_ = 0;
  // The grid's framing (SpacePerception::grid_frame: its tallest body, or the band where its
  // bodies differ): the cells see camera_ scaled by it; the previews keep camera_, so the best
  // and the start compare by height. The version counts its changes (the cells redraw on
  // camera or framing changes).
  GridFrame grid_frame_;
  int grid_frame_version_ = 0;
  std::vector<Eigen::VectorXd> framed_points_;  // the points grid_frame_ is for
  bool framed_close_ups_ = false;               // and the framing it is for
  int toolbar_rows_drawn_ = 0;  // rows the toolbar took last frame (0: none drawn yet)
  bool orbiting_ = false;       // orbit() was called since the last build() (benchmark frames)

  std::vector<CellView> cells_;
  CellView best_, start_, inspect_;
  int cell_pixels_ = 300;
  int sent_cell_pixels_ = 0;  // the last size told to the controller
  int preview_w_ = 260;
  int preview_h_ = 320;
  float dpi_ = 1.0f;

  GridPanel grid_;
  MeasurementsPanel measurements_;
  SlidersPanel sliders_;
  HistoryPanel history_;
  SavePanel save_;
  NewSearchPanel new_search_;
  std::string shown_tab_;    // the tab ImGui showed last frame
  std::string pending_tab_;  // a tab chosen by the program (a dropped file: New search)
  bool confirm_start_over_ = false;
};

}  // namespace app
