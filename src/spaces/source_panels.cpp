#include "spaces/source_panels.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "spaces/space_factory.hpp"

namespace spaces {

namespace fs = std::filesystem;

namespace {

// ui.json's names for what the panels remember (as the window wrote them before kinds were
// registered, so remembered choices survive).
constexpr const char* kBodyModelKey = "body_model";
constexpr const char* kBodyModelFileKey = "body_model_file";
constexpr const char* kPhotoFileKey = "photo_file";

std::string remembered(const app::SourceMemory& memory, const char* key) {
  const auto it = memory.find(key);
  return it == memory.end() ? std::string() : it->second;
}

bool is_builtin_body_model(const std::string& name) {
  const auto& names = builtin_body_models();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A file the session and the prefs keep wherever the program is started from next.
std::string absolute_file(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  return ec ? path : absolute.lexically_normal().string();
}

void no_such_file_note(const std::string& path) {
  std::error_code ec;
  if (!path.empty() && !fs::exists(path, ec)) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "No such file");
  }
}

// Neutral / Female / Male / File...: the built-in models by name, or a model file chosen with
// the file dialog (or typed, or dropped on the window).
class BodySourcePanel final : public app::SourcePanel {
 public:
  explicit BodySourcePanel(const app::SourceMemory& memory)
      : file_(remembered(memory, kBodyModelFileKey)) {
    select(remembered_body_model(memory));
  }

  void draw(app::SourcePanelHost& host) override {
    ImGui::TextUnformatted("Body model:");
    for (const std::string& name : builtin_body_models()) {
      std::string label = name;
      label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
      ImGui::SameLine();
      if (ImGui::RadioButton(label.c_str(), choice_ == name)) choose(name, host);
      host.note_widget("model:" + name);
    }
    ImGui::SameLine();
    if (ImGui::RadioButton("File...", choice_ == "file")) choose("file", host);
    host.note_widget("model:file");
    if (choice_ != "file") return;
    ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 90.0f));
    ImGui::InputTextWithHint("##modelfile", "model .npz", &file_);
    ImGui::SameLine();
    if (ImGui::Button("Browse...")) browse(host);
    host.note_widget("model:browse");
    if (file_.empty()) {
      ImGui::TextDisabled(
          "Choose an SMPL-layout .npz (an SMPL .pkl: convert it first, see README)");
    }
    no_such_file_note(file_);
  }

  std::optional<std::string> chosen_source() const override {
    if (choice_ != "file") return choice_;
    std::error_code ec;
    if (file_.empty() || !fs::exists(file_, ec)) return std::nullopt;
    return absolute_file(file_);
  }

  void use_file(const std::string& path) override {
    choice_ = "file";
    file_ = path;
  }

  void opened(const std::string& source, bool asked_here, app::SourceMemory& memory) override {
    // A search this panel started has opened: its model is the one to start with next time.
    // (A resumed session or a --model is not a choice made here, and a file that failed to
    // load never gets this far.)
    if (asked_here) {
      memory[kBodyModelKey] = source.empty() ? "neutral" : source;
      if (!is_builtin_body_model(memory[kBodyModelKey])) memory[kBodyModelFileKey] = source;
    }
    select(source);
  }

  std::string choice() const override { return choice_; }

  void choose(const std::string& choice, app::SourcePanelHost& host) override {
    if (choice == "file") {
      choice_ = "file";
      if (file_.empty()) browse(host);
      return;
    }
    if (is_builtin_body_model(choice)) choice_ = choice;
  }

 private:
  void select(const std::string& source) {
    if (source.empty()) {
      choice_ = "neutral";
    } else if (is_builtin_body_model(source)) {
      choice_ = source;
    } else {
      choice_ = "file";
      file_ = source;
    }
  }

  void browse(app::SourcePanelHost& host) {
    // .pkl too, so that choosing one says how to convert it.
    host.browse("Choose a body model", {".npz", ".pkl"}, file_);
  }

  std::string choice_ = "neutral";
  std::string file_;
};

class PhotoSourcePanel final : public app::SourcePanel {
 public:
  explicit PhotoSourcePanel(const app::SourceMemory& memory)
      : file_(remembered(memory, kPhotoFileKey)) {}

  void draw(app::SourcePanelHost& host) override {
    ImGui::TextUnformatted("Photo (.png/.jpg; empty = the built-in landscape; or drop one here)");
    ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 90.0f));
    ImGui::InputTextWithHint("##source", "built-in landscape", &file_);
    host.note_widget("photo:file");
    ImGui::SameLine();
    if (ImGui::Button("Browse...##photo")) browse(host);
    host.note_widget("photo:browse");
    no_such_file_note(file_);
  }

  std::optional<std::string> chosen_source() const override {
    if (file_.empty()) return std::string();
    std::error_code ec;
    if (!fs::exists(file_, ec)) return std::nullopt;
    return absolute_file(file_);
  }

  void use_file(const std::string& path) override { file_ = path; }

  void opened(const std::string& source, bool /*asked_here*/, app::SourceMemory& memory) override {
    // A picture that opened is the one offered next time (also after a relaunch).
    if (!source.empty()) {
      file_ = source;
      memory[kPhotoFileKey] = source;
    }
  }

  std::string choice() const override { return file_.empty() ? "built-in" : "file"; }

  void choose(const std::string& choice, app::SourcePanelHost& host) override {
    if (choice == "built-in") file_.clear();
    if (choice == "file") browse(host);
  }

 private:
  void browse(app::SourcePanelHost& host) {
    host.browse("Choose a photo", {".png", ".jpg", ".jpeg"}, file_);
  }

  std::string file_;
};

}  // namespace

std::unique_ptr<app::SourcePanel> make_body_source_panel(const app::SourceMemory& memory) {
  return std::make_unique<BodySourcePanel>(memory);
}

std::unique_ptr<app::SourcePanel> make_photo_source_panel(const app::SourceMemory& memory) {
  return std::make_unique<PhotoSourcePanel>(memory);
}

std::string remembered_body_model(const app::SourceMemory& memory) {
  const std::string model = remembered(memory, kBodyModelKey);
  return model.empty() ? "neutral" : model;
}

}  // namespace spaces
