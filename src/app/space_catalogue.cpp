#include "app/space_catalogue.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace app {

void SpaceCatalogue::add(SpaceKind kind) {
  if (kind.name.empty() || !kind.open) {
    throw std::logic_error("a design space kind needs a name and an open function");
  }
  if (find(kind.name) != nullptr) {
    throw std::logic_error("design space kind '" + kind.name + "' registered twice");
  }
  kinds_.push_back(std::move(kind));
}

const SpaceKind& SpaceCatalogue::default_kind() const {
  if (kinds_.empty()) throw std::logic_error("no design space kind is registered");
  return kinds_.front();
}

const SpaceKind* SpaceCatalogue::find(const std::string& name) const {
  for (const SpaceKind& k : kinds_) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

const SpaceKind& SpaceCatalogue::get(const std::string& name) const {
  if (const SpaceKind* k = find(name)) return *k;
  throw std::runtime_error("unknown design space '" + name + "' (known: " + names() + ")");
}

const SpaceKind* SpaceCatalogue::kind_for_file(const std::filesystem::path& path) const {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (ext.empty()) return nullptr;
  for (const SpaceKind& k : kinds_) {
    if (std::find(k.file_extensions.begin(), k.file_extensions.end(), ext) !=
        k.file_extensions.end()) {
      return &k;
    }
  }
  return nullptr;
}

SpaceSettings SpaceCatalogue::default_settings(const std::string& kind) const {
  const SpaceKind& k = get(kind);
  SpaceSettings s;
  s.kind = k.name;
  s.dimensions = k.dimensions;
  return s;
}

std::unique_ptr<DesignSpace> SpaceCatalogue::open(const SpaceSettings& settings) const {
  const SpaceKind& kind = settings.kind.empty() ? default_kind() : get(settings.kind);
  SpaceSettings s = settings;
  s.kind = kind.name;
  if (s.dimensions <= 0) s.dimensions = kind.dimensions;
  return kind.open(s);
}

std::string SpaceCatalogue::names(const std::string& separator) const {
  std::string out;
  for (const SpaceKind& k : kinds_) out += (out.empty() ? "" : separator) + k.name;
  return out;
}

}  // namespace app
