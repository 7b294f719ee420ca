#include "app/ui_prefs.hpp"

#include <algorithm>
#include <set>

#include <nlohmann/json.hpp>

#include "app/session_store.hpp"
#include "sps/json_fields.hpp"
#include "util/atomic_file.hpp"
#include "util/file_read.hpp"

namespace app {

std::filesystem::path ui_prefs_path(const std::filesystem::path& session_path) {
  return session_path.parent_path() / "ui.json";
}

namespace {

// ui.json holds a few short fields; anything larger is not ours.
constexpr std::size_t kMaxPrefsBytes = 1u << 20;

// The window's own fields; any other string field is a source panel's.
const std::set<std::string> kPrefsFields{
    "window_width", "window_height", "save_folder", "save_name",  "view_preset", "close_ups",
    "side_tab",     "typed_targets", "imperial",    "open_panel", "save_panel",  "history_panel"};

// Moves a broken ui.json out of the way (never deleted: it may be something the user put there
// by mistake) and says where it went.
std::string set_aside(const std::filesystem::path& path, const std::string& why) {
  const std::filesystem::path aside = unused_name_beside(path, "corrupt");
  std::error_code ec;
  std::filesystem::rename(path, aside, ec);
  std::string text = "the remembered window settings " + why + "; using defaults";
  if (ec) return text + " (could not move it aside: " + ec.message() + ")";
  return text + " and moved it to " + aside.string();
}

}  // namespace

UiPrefs load_ui_prefs(const std::filesystem::path& path, std::string* problem) {
  UiPrefs p;
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return p;
  nlohmann::json j;
  std::string why;
  try {
    j = sps::json_fields::parse_bounded(util::read_regular_file(path, kMaxPrefsBytes),
                                        {kMaxPrefsBytes, 8, 8192});
    if (!j.is_object()) why = "(" + path.string() + ") are not a JSON object";
  } catch (const util::FileReadError& e) {
    why = "cannot be read (" + std::string(e.what()) + ")";
  } catch (const std::exception& e) {
    why = "(" + path.string() + ") are broken: " + e.what();
  }
  if (!why.empty()) {
    const std::string text = set_aside(path, why);
    if (problem != nullptr) *problem = text;
    return p;
  }
  auto get_int = [&](const char* key, int fallback, int lo, int hi) {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number_integer()) return fallback;
    return std::clamp(it->get<int>(), lo, hi);
  };
  auto get_string = [&](const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
  };
  auto get_bool = [&](const char* key, bool fallback) {
    const auto it = j.find(key);
    return it != j.end() && it->is_boolean() ? it->get<bool>() : fallback;
  };
  p.window_width = get_int("window_width", 0, 320, 16384);
  p.window_height = get_int("window_height", 0, 240, 16384);
  if (p.window_width == 0 || p.window_height == 0) p.window_width = p.window_height = 0;
  p.save_folder = get_string("save_folder");
  p.save_name = get_string("save_name");
  p.view_preset = get_int("view_preset", 0, 0, 2);
  if (const std::string tab = get_string("side_tab"); !tab.empty() && tab.size() <= 32) {
    p.side_tab = tab;
  }
  p.imperial = get_bool("imperial", false);
  p.close_ups = get_bool("close_ups", true);
  // Every other short string field belongs to a kind's source panel.
  for (const auto& [name, value] : j.items()) {
    if (p.sources.size() >= 32) break;
    if (!value.is_string() || name.size() > 32 || kPrefsFields.count(name) != 0) continue;
    if (value.get_ref<const std::string&>().size() <= 4096) p.sources[name] = value;
  }
  if (const auto it = j.find("typed_targets"); it != j.end() && it->is_object()) {
    // Short texts under short names only: anything else is not what this window wrote.
    for (const auto& [name, text] : it->items()) {
      if (p.typed_targets.size() >= 32) break;
      if (name.size() <= 32 && text.is_string() &&
          text.get_ref<const std::string&>().size() <= 32) {
        p.typed_targets[name] = text.get<std::string>();
      }
    }
  }
  return p;
}

bool save_ui_prefs(const UiPrefs& p, const std::filesystem::path& path) {
  nlohmann::json j = {{"window_width", p.window_width},   {"window_height", p.window_height},
                      {"save_folder", p.save_folder},     {"save_name", p.save_name},
                      {"view_preset", p.view_preset},     {"side_tab", p.side_tab},
                      {"typed_targets", p.typed_targets}, {"imperial", p.imperial},
                      {"close_ups", p.close_ups}};
  for (const auto& [name, value] : p.sources) {
    if (kPrefsFields.count(name) == 0) j[name] = value;
  }
  try {
    util::write_file_atomically(path, j.dump(1), /*create_folders=*/true);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

UiPrefsSaver::UiPrefsSaver(std::filesystem::path path, UiPrefs saved, double delay_seconds)
    : path_(std::move(path)), saved_(std::move(saved)), delay_(delay_seconds) {}

bool UiPrefsSaver::update(const UiPrefs& current, double now_seconds) {
  if (current == saved_) {
    pending_ = false;
    return false;
  }
  if (!pending_ || current != pending_prefs_) {
    pending_ = true;
    pending_prefs_ = current;
    changed_at_ = now_seconds;
    return false;
  }
  if (now_seconds - changed_at_ < delay_) return false;
  if (write(current)) return true;
  changed_at_ = now_seconds;  // failed (full disk, folder gone): try again after a delay
  return false;
}

bool UiPrefsSaver::flush(const UiPrefs& current) {
  pending_ = false;
  return current == saved_ || write(current);
}

bool UiPrefsSaver::write(const UiPrefs& current) {
  if (!save_ui_prefs(current, path_)) return false;
  saved_ = current;
  pending_ = false;
  ++writes_;
  return true;
}

}  // namespace app
