// Choosing a file: the desktop's own dialog (zenity on GNOME, kdialog on KDE) when one is
// installed and wanted, else a small in-app browser. One dialog at a time; the answer is
// collected by the panel that asked, by its tag.
#pragma once

#include <filesystem>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <vector>

namespace app {

struct FileRequest {
  std::string tag;    // who asked: "save", "source"
  std::string title;  // "Save as", "Choose a body model"
  bool save = false;  // choosing a new file name (else an existing file)
  // Opening: the extensions offered (".npz"); the browser lists folders and these only.
  std::vector<std::string> extensions;
  std::string filter_label;     // "Body models"
  std::filesystem::path start;  // a file (its folder and name) or a folder; empty: here
};

struct FileAnswer {
  std::string tag;
  std::filesystem::path path;
};

class FileDialogs {
 public:
  // `desktop`: use the desktop's dialog when installed (tests and --file-dialog builtin: never).
  explicit FileDialogs(bool desktop) : use_desktop_(desktop) {}
  // False (and nothing opens) while another dialog is open.
  bool open(const FileRequest& request);
  bool is_open() const { return browser_open_ || desktop_answer_.valid(); }
  // A desktop dialog runs as a child process (the window keeps polling).
  bool waiting_for_desktop() const { return desktop_answer_.valid(); }
  // Every frame, inside the main ImGui window: the in-app browser when it is open. `note`
  // names its widgets ("browser:name", "browser:ok") for scripted tests.
  void draw(const std::function<void(const std::string&)>& note);
  // The answer to the last request, once (cancelled: never).
  std::optional<FileAnswer> take_answer();

 private:
  void open_browser(const FileRequest& request);

  bool use_desktop_;
  FileRequest request_;
  bool browser_open_ = false;
  std::string browser_dir_;
  std::string browser_name_;
  std::optional<std::filesystem::path> browser_answer_;
  std::future<std::optional<std::string>> desktop_answer_;
};

}  // namespace app
