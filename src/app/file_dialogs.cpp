#include "app/file_dialogs.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace app {

namespace fs = std::filesystem;

namespace {

std::string find_program(const char* name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  const std::string dirs = path;
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

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

// The desktop dialog's command line, or "" when neither zenity nor kdialog is installed.
std::string desktop_command(const FileRequest& r, const fs::path& start_file) {
  const std::string start = shell_quote(start_file.string());
  std::string patterns;  // "*.png *.PNG"
  for (const std::string& ext : r.extensions) {
    std::string upper = ext;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    patterns += (patterns.empty() ? "*" : " *") + ext + " *" + upper;
  }
  if (const std::string zenity = find_program("zenity"); !zenity.empty()) {
    std::string command = shell_quote(zenity) + " --file-selection --title=" + shell_quote(r.title);
    if (r.save) command += " --save";
    if (!r.save && !patterns.empty()) {
      command += " --file-filter=" + shell_quote(r.filter_label + " | " + patterns) +
                 " --file-filter='All files | *'";
    }
    return command + " --filename=" + start + " 2>/dev/null";
  }
  if (const std::string kdialog = find_program("kdialog"); !kdialog.empty()) {
    if (r.save) return shell_quote(kdialog) + " --getsavefilename " + start + " 2>/dev/null";
    return shell_quote(kdialog) + " --getopenfilename " + start + " " +
           shell_quote(patterns + "|" + r.filter_label) + " 2>/dev/null";
  }
  return "";
}

}  // namespace

bool FileDialogs::open(const FileRequest& request) {
  if (is_open()) return false;
  request_ = request;
  std::error_code ec;
  const fs::path start = request.start.empty() ? fs::current_path(ec) : request.start;
  if (use_desktop_) {
    if (const std::string command = desktop_command(request, start); !command.empty()) {
      desktop_answer_ = std::async(std::launch::async, [command] { return run_dialog(command); });
      return true;
    }
  }
  open_browser(request);
  return true;
}

void FileDialogs::open_browser(const FileRequest& request) {
  std::error_code ec;
  const fs::path start = request.start;
  const bool is_folder = !start.empty() && fs::is_directory(start, ec);
  fs::path folder = is_folder ? start : start.parent_path();
  if (folder.empty()) folder = fs::current_path(ec);
  browser_dir_ = fs::absolute(folder, ec).string();
  browser_name_ = is_folder ? std::string() : start.filename().string();
  browser_open_ = true;
}

std::optional<FileAnswer> FileDialogs::take_answer() {
  if (browser_answer_) {
    FileAnswer a{request_.tag, *browser_answer_};
    browser_answer_.reset();
    return a;
  }
  if (desktop_answer_.valid() &&
      desktop_answer_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    if (const auto path = desktop_answer_.get()) return FileAnswer{request_.tag, *path};
  }
  return std::nullopt;
}

void FileDialogs::draw(const std::function<void(const std::string&)>& note) {
  if (!browser_open_) return;
  const char* title = request_.title.c_str();
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
    // Opening: folders and the files asked for only; saving: everything, to see the names.
    const std::string ext = lower_extension(it->path());
    const bool wanted = request_.save || request_.extensions.empty() ||
                        std::find(request_.extensions.begin(), request_.extensions.end(), ext) !=
                            request_.extensions.end();
    if (!it->is_directory(e1) && !wanted) continue;
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
  note("browser:name");
  if (ImGui::Button(request_.save ? "Save" : "Open", ImVec2(120, 0)) && !browser_name_.empty()) {
    browser_answer_ = dir / browser_name_;
    browser_open_ = false;
    ImGui::CloseCurrentPopup();
  }
  note("browser:ok");
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0))) {
    browser_open_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace app
