// The Save tab: where the shown body or photo is written, Save / Save as..., and the question
// before a file this search did not write is replaced.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "app/panel_context.hpp"

namespace app {

// Where Save puts a file when no folder was chosen yet: ~/Documents if it exists, else ~.
std::filesystem::path default_save_folder();

class SavePanel {
 public:
  // `path`: --save-path, else the remembered folder and name (prefs), else the space's name in
  // default_save_folder() once a space is open.
  SavePanel(const std::string& path, const UiPrefs& prefs);
  // A space opened: a name of another file type becomes the space's default name.
  void space_opened(const DesignSpace& space, const UiPrefs& prefs);
  void draw(PanelContext& ctx);
  // The "Replace file?" question, while it is asked (drawn among the window's modals).
  void draw_question(PanelContext& ctx);
  // Save (Ctrl+S): to the field's path, asking before replacing a file this search did not
  // write; with no path, Save as....
  void quick_save(PanelContext& ctx);
  void open_dialog(PanelContext& ctx);
  // The file dialog's answer for "save".
  void file_chosen(PanelContext& ctx, const std::filesystem::path& path);
  const std::optional<std::filesystem::path>& question() const { return confirm_overwrite_; }
  const std::string& path() const { return path_; }

 private:
  void request_export(PanelContext& ctx, const std::filesystem::path& path);

  std::string path_;
  std::optional<std::filesystem::path> confirm_overwrite_;
};

}  // namespace app
