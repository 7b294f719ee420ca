#include "app/ui_prefs.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "util/atomic_file.hpp"

namespace app {

std::filesystem::path ui_prefs_path(const std::filesystem::path& session_path) {
  return session_path.parent_path() / "ui.json";
}

UiPrefs load_ui_prefs(const std::filesystem::path& path) {
  UiPrefs p;
  std::ifstream in(path);
  if (!in) return p;
  std::ostringstream text;
  text << in.rdbuf();
  const auto j = nlohmann::json::parse(text.str(), nullptr, false);
  if (!j.is_object()) return p;
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
  p.open_panel = get_bool("open_panel", p.open_panel);
  p.save_panel = get_bool("save_panel", p.save_panel);
  p.history_panel = get_bool("history_panel", p.history_panel);
  if (const std::string model = get_string("body_model"); !model.empty()) p.body_model = model;
  p.body_model_file = get_string("body_model_file");
  return p;
}

bool save_ui_prefs(const UiPrefs& p, const std::filesystem::path& path) {
  const nlohmann::json j = {
      {"window_width", p.window_width}, {"window_height", p.window_height},
      {"save_folder", p.save_folder},   {"save_name", p.save_name},
      {"view_preset", p.view_preset},   {"open_panel", p.open_panel},
      {"save_panel", p.save_panel},     {"history_panel", p.history_panel},
      {"body_model", p.body_model},     {"body_model_file", p.body_model_file}};
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
