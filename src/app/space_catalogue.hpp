// The kinds of design space the gallery can search, as a catalogue the spaces fill in
// (src/spaces registers body and photo). The window, the controller and the command line ask
// the catalogue for a kind's name, label, defaults, file types and its New-search source panel,
// so a third space is a set of new files and one registration, not edits of the window.
// No GL and no ImGui here.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/design_space.hpp"

namespace app {

// What a source panel may ask of the window it is drawn in.
class SourcePanelHost {
 public:
  virtual ~SourcePanelHost() = default;
  // Opens the file dialog for an existing file of these extensions (".npz"), starting at
  // `start` (a file or a folder; empty: the current folder). The answer reaches the panel's
  // use_file().
  virtual void browse(const std::string& title, const std::vector<std::string>& extensions,
                      const std::filesystem::path& start) = 0;
  // Remembers where the last widget drawn was, under `name`, for scripted tests.
  virtual void note_widget(const std::string& name) = 0;
};

// What a kind remembers between launches in the window's ui.json: a few named strings
// ("body_model" -> "female"). The names are the kind's own.
using SourceMemory = std::map<std::string, std::string>;

// The New-search panel's part that belongs to one kind: which model or picture a new search
// starts on. Drawn with ImGui by the space that registers it.
class SourcePanel {
 public:
  virtual ~SourcePanel() = default;
  virtual void draw(SourcePanelHost& host) = 0;
  // The source of the search it would start (SpaceSettings::source, "" for the built-in
  // default), or nothing while none can start (a file not chosen or not there).
  virtual std::optional<std::string> chosen_source() const = 0;
  // A file dropped on the window or chosen in the dialog.
  virtual void use_file(const std::string& path) = 0;
  // A search of this kind opened on `source`: the panel shows it from now on. `asked_here`: the
  // panel's own choice (remembered for the next launch), not a resumed or command-line search.
  virtual void opened(const std::string& source, bool asked_here, SourceMemory& memory) = 0;
  // The panel's choice in words, as its radio buttons read it ("female", "file"); tests and
  // scripted runs choose with choose().
  virtual std::string choice() const = 0;
  virtual void choose(const std::string& choice, SourcePanelHost& host) = 0;
};

struct SpaceKind {
  std::string name;               // as sessions store it: "body"
  std::string label;              // the New-search radio button: "body shape"
  std::string source_noun;        // the toolbar: "Model", "Photo"
  std::string source_option;      // the command-line option naming the source: "model", "image"
  int dimensions = 10;            // a new search's default dimension count
  bool dimensions_fixed = false;  // the space always has `dimensions` (the panel hides them)
  int grid_size = 3;              // the default grid
  // Files that start a search of this kind when dropped on the window (".png", lower case).
  std::vector<std::string> file_extensions;
  // Opens a space of this kind; throws with a message naming the file and the problem.
  std::function<std::unique_ptr<DesignSpace>(const SpaceSettings&)> open;
  // "on the female model", "on beach.jpg": a new search's source for the confirmation question.
  std::function<std::string(const std::string& source)> describe_source;
  // The source a launch without one starts on, from what the kind remembered ("" : the
  // built-in default).
  std::function<std::string(const SourceMemory&)> remembered_source;
  // The kind's New-search panel (GUI builds only; empty without one).
  std::function<std::unique_ptr<SourcePanel>(const SourceMemory&)> make_source_panel;
};

class SpaceCatalogue {
 public:
  // The first kind added is the default one (a session file that names none, a launch
  // without --space).
  void add(SpaceKind kind);
  const std::vector<SpaceKind>& kinds() const { return kinds_; }
  const SpaceKind& default_kind() const;
  // nullptr for an unknown name.
  const SpaceKind* find(const std::string& name) const;
  // Throws std::runtime_error "unknown design space 'x' (known: body, photo)".
  const SpaceKind& get(const std::string& name) const;
  // The kind a file of this extension opens (case-insensitive), nullptr for none.
  const SpaceKind* kind_for_file(const std::filesystem::path& path) const;
  // A new search of `kind` with its defaults.
  SpaceSettings default_settings(const std::string& kind) const;
  // Opens `settings`; an empty kind means the default kind, no dimensions the kind's own.
  std::unique_ptr<DesignSpace> open(const SpaceSettings& settings) const;
  // "body, photo".
  std::string names(const std::string& separator = ", ") const;

 private:
  std::vector<SpaceKind> kinds_;
};

}  // namespace app
