// What every panel of the window is drawn with: the controller it reads and queues intents on,
// the remembered settings it may change, the file dialogs and the record of where its widgets
// were (for scripted tests). Panels change no search state themselves.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "app/file_dialogs.hpp"
#include "app/gallery_controller.hpp"
#include "app/gallery_layout.hpp"
#include "app/space_catalogue.hpp"
#include "app/ui_prefs.hpp"

namespace app {

// Where named widgets of the last frame were, in window pixels ("model:female", "new-search").
class WidgetNotes {
 public:
  explicit WidgetNotes(bool report) : report_(report) {}
  // Records the last item ImGui drew under `name` (and prints it when it moved, if reporting).
  void note(const std::string& name);
  std::optional<LayoutRect> find(const std::string& name) const;

 private:
  bool report_;
  std::map<std::string, LayoutRect> rects_;
};

struct PanelContext {
  GalleryController& c;
  UiPrefs& prefs;
  FileDialogs& dialogs;
  WidgetNotes& widgets;
  const SpaceCatalogue& catalogue;
};

// A GL texture name as ImGui takes it.
inline void* texture_id(unsigned int texture) {
  return reinterpret_cast<void*>(static_cast<std::intptr_t>(texture));
}

}  // namespace app
