// The gallery's panels (Dear ImGui): they read the controller's state and queue intents; they
// change nothing themselves. Also owns what is drawn on the GPU for the current frame (grid
// cells, previews, history thumbnails), rendered before the UI frame starts, and the camera.
#pragma once

#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cell_view.hpp"
#include "app/gallery_controller.hpp"
#include "app/gallery_layout.hpp"
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

// Where Save puts a file when no folder was chosen yet: ~/Documents if it exists, else ~.
std::filesystem::path default_save_folder();

class GalleryView {
 public:
  GalleryView(ViewOptions options, UiPrefs prefs);
  ~GalleryView();

  // Before the UI frame, after the controller applied its intents: lays the window out and
  // prepares (CPU) and uploads every cell whose point changed. `dpi` = framebuffer / window
  // pixels.
  void update_cells(GalleryController& c, float width, float height, float dpi);
  // Then renders every cell whose content, size or camera changed into its framebuffer.
  void draw_cells(GalleryController& c);
  // Builds the ImGui panels for this frame; input becomes intents queued on `c`.
  void build(GalleryController& c, long frame);

  // Keyboard shortcuts, translated by the window: a cell by its label (0-based index), undo,
  // redo, save.
  void press_cell(GalleryController& c, int index);
  void quick_save(GalleryController& c);
  // A file dropped on the window: the model or image for a new search (asks first if the
  // current search has progress).
  void open_dropped(GalleryController& c, const std::string& path);
  // The file Save is asking before replacing, if it is asking.
  const std::optional<std::filesystem::path>& overwrite_question() const {
    return confirm_overwrite_;
  }
  // How many history thumbnails were drawn so far (each once: tests check that orbiting the
  // grid draws none).
  long thumbnail_draws() const { return thumbnail_draws_; }
  // Switches the view preset (0 front, 1 side, 2 three-quarter), as its toolbar button does.
  void choose_view(int index) { set_preset(index); }
  // Turns the shared camera as dragging across a cell does (bench-gui's orbit frames).
  void orbit(float dx, float dy);
  // A dialog or question is open (the window keeps polling).
  bool waiting_for_dialog() const { return desktop_dialog_.valid(); }

  // The New-search panel's body model: "neutral", "female", "male" (built in) or "file" (then
  // model_file() is the file). What the panel's buttons call; tests call them too.
  const std::string& model_choice() const { return open_model_; }
  const std::string& model_file() const { return open_model_file_; }
  void choose_model(const std::string& choice);  // "file" with no file yet opens the dialog
  void set_model_file(const std::string& path);  // also chooses "file"
  // "Open / apply": a new search with the panel's settings (asks first if the current search
  // has progress, as a dropped file does).
  void start_new_search(GalleryController& c);
  // Where a named widget of the last frame was, in window pixels ("model:female",
  // "model:file", "new-search", "panel:new-search", "confirm:start"), for scripted tests.
  std::optional<LayoutRect> widget(const std::string& name) const;

  const GalleryLayout& layout() const { return layout_; }
  int cell_pixels() const { return cell_pixels_; }
  int hovered_cell() const { return hovered_; }
  bool text_input_active() const;
  const UiPrefs& prefs() const { return prefs_; }
  std::string save_path() const { return save_path_; }
  // Drops every GL object (before the context goes).
  void release_gl();
  // Label of cell `index` on an n x n grid: 1-9 on 3x3, A-Y on 5x5 (also its key).
  static std::string cell_label(int index, int n);

 private:
  void sync_space(GalleryController& c);
  void draw_toolbar(GalleryController& c);
  void draw_messages(const GalleryController& c);
  void draw_grid(GalleryController& c, long frame);
  void draw_side_panel(GalleryController& c);
  void draw_history(GalleryController& c);
  void draw_save(GalleryController& c);
  void draw_open(GalleryController& c);
  void draw_sliders(GalleryController& c);
  void draw_modals(GalleryController& c);
  void draw_model_picker();
  void select_model_source(const std::string& source);
  void draw_file_browser();
  // (centre_x, centre_y): the grid's centre on screen; the tooltip opens towards it.
  // The hovered cell against the current best: a one-line summary inside the cell (it covers
  // no neighbour); the full table while Shift is held.
  void draw_hover_details(const GalleryController& c, const LayoutRect& cell, float centre_x,
                          float centre_y);
  void request_export(GalleryController& c, const std::filesystem::path& path);
  void open_save_dialog(GalleryController& c);
  void open_image_dialog();
  void open_model_dialog();
  void open_file_dialog(const std::filesystem::path& folder, const std::string& name);
  void file_chosen(GalleryController& c, const std::filesystem::path& path);
  void poll_desktop_dialog(GalleryController& c);
  void note_widget(const std::string& name);
  void set_preset(int index);

  ViewOptions options_;
  UiPrefs prefs_;
  GalleryLayout layout_;
  int space_generation_ = -1;

  render::Camera camera_;
  int active_preset_ = 0;  // -1 after a free orbit
  int camera_version_ = 0;
  bool camera_dragging_ = false;
  bool second_of_double_ = false;  // the press being released is a double-click's second

  std::vector<CellView> cells_;
  CellView best_, start_, inspect_;
  // History thumbnails: only their pictures. Each is drawn once, from the front, and keeps no
  // mesh or prepared data, so neither orbiting nor a long session makes them cost more.
  struct Thumbnail {
    Eigen::VectorXd x;
    render::CellFramebuffer fbo;
    bool drawn = false;
  };
  std::vector<Thumbnail> history_;
  render::Camera thumbnail_camera_;
  long thumbnail_draws_ = 0;
  int cell_pixels_ = 300;
  int sent_cell_pixels_ = 0;  // the last size told to the controller
  int preview_w_ = 260;
  int preview_h_ = 320;
  float dpi_ = 1.0f;
  int hovered_ = -1;
  std::shared_ptr<const PreparedCell> hover_details_;

  // Fields of the panels (what the user typed; intents carry copies).
  std::string save_path_;
  std::string open_kind_ = "body";
  std::string open_source_;  // the photo file (bodies: the model picker below)
  std::string open_model_ = "neutral";
  std::string open_model_file_;
  std::string open_photo_file_;  // the last picture opened (prefs), offered for a photo search
  // The body model of a new search this view asked for; remembered in the prefs once that
  // search has opened (a file that fails to load is not remembered).
  std::optional<std::string> requested_model_;
  int open_dims_ = 10;
  int open_grid_ = 3;
  int open_zoom_ = 4;

  MeasurementPanelState measurement_panel_;

  // Expert sliders: while set, the "current best" preview shows this point instead.
  std::optional<Eigen::VectorXd> slider_x_;
  bool sliders_panel_ = false;

  // Questions pending an answer.
  std::optional<intent::Open> confirm_open_;
  std::optional<std::filesystem::path> confirm_overwrite_;
  bool confirm_start_over_ = false;
  // What the file dialog (desktop or in-app) is choosing.
  enum class DialogPurpose { kSave, kOpenModel, kOpenImage };
  DialogPurpose dialog_purpose_ = DialogPurpose::kSave;
  // The in-app file browser.
  bool browser_open_ = false;
  std::string browser_dir_;
  std::string browser_name_;
  std::optional<std::filesystem::path> browser_result_;
  // The desktop's dialog runs as a child process; its answer arrives here.
  std::future<std::optional<std::string>> desktop_dialog_;
  std::map<std::string, LayoutRect> widgets_;
};

}  // namespace app
