// What the window remembers between launches: its size, the last folder and file name saved
// to, the view, the side panel's tab and what each kind of search last started on. A small JSON
// file beside the session file; a missing or broken one means defaults (it is a convenience,
// never user work), and a broken one is reported and set aside.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace app {

struct UiPrefs {
  int window_width = 0;  // 0 = not known yet
  int window_height = 0;
  std::string save_folder;
  std::string save_name;
  int view_preset = 0;  // 0 front, 1 side, 2 three-quarter
  // Body grids framed on where their cells differ (DesignSpace::set_close_ups), or whole.
  bool close_ups = true;
  // The side panel's open tab (see side_panel_tabs() in gallery_view.hpp).
  std::string side_tab = "measurements";
  // What each kind of search remembers for its New-search panel, under the kind's own names
  // (a body search: "body_model" -> "female"). Stored as top-level strings, so files from
  // before the catalogue of kinds read the same.
  std::map<std::string, std::string> sources;
  // The measurement panel: typed targets not yet used ("height" -> "180cm"), and its units.
  std::map<std::string, std::string> typed_targets;
  bool imperial = false;

  bool operator==(const UiPrefs& o) const {
    return window_width == o.window_width && window_height == o.window_height &&
           save_folder == o.save_folder && save_name == o.save_name &&
           view_preset == o.view_preset && close_ups == o.close_ups && side_tab == o.side_tab &&
           sources == o.sources && typed_targets == o.typed_targets && imperial == o.imperial;
  }
  bool operator!=(const UiPrefs& o) const { return !(*this == o); }
};

// "<session folder>/ui.json".
std::filesystem::path ui_prefs_path(const std::filesystem::path& session_path);
// A missing file gives defaults. A file that cannot be used (not a regular file, over 1 MB,
// not a JSON object, nested too deep) gives defaults too, is moved aside as
// "ui.json.corrupt-<time>" and is described in `problem` for the window to show.
UiPrefs load_ui_prefs(const std::filesystem::path& path, std::string* problem = nullptr);
// Atomic; returns false (and leaves the old file) when it cannot be written.
bool save_ui_prefs(const UiPrefs& prefs, const std::filesystem::path& path);

// Writes the prefs when they change rather than only at a normal close (a crash, a kill or a
// logout would lose them), once they have stayed the same for `delay_seconds`: a window being
// resized changes them every frame. Each write is atomic (save_ui_prefs).
class UiPrefsSaver {
 public:
  // `saved`: what the file holds now (what load_ui_prefs returned).
  UiPrefsSaver(std::filesystem::path path, UiPrefs saved, double delay_seconds = 1.0);
  // Every frame, with the current prefs; true when it wrote the file in this call. A write that
  // fails is tried again after another delay.
  bool update(const UiPrefs& current, double now_seconds);
  // At exit: writes now if `current` is not what the file holds; false if that write failed.
  bool flush(const UiPrefs& current);
  int writes() const { return writes_; }

 private:
  bool write(const UiPrefs& current);

  std::filesystem::path path_;
  UiPrefs saved_;
  double delay_;
  bool pending_ = false;
  UiPrefs pending_prefs_;
  double changed_at_ = 0.0;
  int writes_ = 0;
};

}  // namespace app
