// The New-search tab: which kind of design (from the catalogue), the kind's own source picker,
// its dimensions, the grid and the clicks per plane; and the question before a search with
// progress is replaced.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "app/panel_context.hpp"

namespace app {

class NewSearchPanel final : public SourcePanelHost {
 public:
  NewSearchPanel(const SpaceCatalogue& catalogue, FileDialogs& dialogs, WidgetNotes& widgets,
                 const UiPrefs& prefs);
  // A space opened (this panel's request, a resume or the command line's): the panel shows its
  // settings, and remembers the source when the panel asked for it.
  void space_opened(const GalleryController& c, UiPrefs& prefs);
  void draw(PanelContext& ctx);
  // "Start the new search?" while it is asked.
  void draw_question(PanelContext& ctx);
  // "Open / apply": a new search with the panel's settings (asks first if the current search
  // has progress).
  void start(PanelContext& ctx);
  // A file dropped on the window: the kind that takes its extension (else the default kind,
  // which says what is wrong with it) starts a new search on it.
  void open_dropped(PanelContext& ctx, const std::string& path);
  // The file dialog's answer for "source".
  void file_chosen(const std::string& path);

  // The shown kind's source picker, as its radio buttons read (tests and scripted runs).
  std::string source_choice() const;
  void choose_source(const std::string& choice);
  void use_source_file(const std::string& path);

  // SourcePanelHost
  void browse(const std::string& title, const std::vector<std::string>& extensions,
              const std::filesystem::path& start) override;
  void note_widget(const std::string& name) override { widgets_.note(name); }

 private:
  SourcePanel* panel(const std::string& kind);
  // A new search of the shown kind on `source` (asks first if the current one has progress).
  void request(PanelContext& ctx, const std::string& source);
  void select_kind(const SpaceKind& kind);

  const SpaceCatalogue& catalogue_;
  FileDialogs& dialogs_;
  WidgetNotes& widgets_;
  SourceMemory memory_;  // the prefs' sources when the panel was made
  std::map<std::string, std::unique_ptr<SourcePanel>> panels_;
  std::string kind_;
  int dims_ = 10;
  int grid_ = 3;
  int zoom_ = 4;
  // The search this panel asked for, remembered by its kind once it has opened (a file that
  // fails to load is not remembered).
  std::optional<SpaceSettings> requested_;
  std::optional<intent::Open> confirm_open_;
};

}  // namespace app
