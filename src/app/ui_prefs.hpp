// What the window remembers between launches: its size, the last folder and file name saved
// to, the view and which panels were open. A small JSON file beside the session file; a
// missing or broken one just means defaults (it is a convenience, never user work).
#pragma once

#include <filesystem>
#include <string>

namespace app {

struct UiPrefs {
  int window_width = 0;  // 0 = not known yet
  int window_height = 0;
  std::string save_folder;
  std::string save_name;
  int view_preset = 0;  // 0 front, 1 side, 2 three-quarter
  bool open_panel = false;
  bool save_panel = true;
  bool history_panel = true;
};

// "<session folder>/ui.json".
std::filesystem::path ui_prefs_path(const std::filesystem::path& session_path);
UiPrefs load_ui_prefs(const std::filesystem::path& path);
// Atomic; returns false (and leaves the old file) when it cannot be written.
bool save_ui_prefs(const UiPrefs& prefs, const std::filesystem::path& path);

}  // namespace app
