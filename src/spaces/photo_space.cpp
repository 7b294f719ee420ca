#include "spaces/photo_space.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "render/photo_renderer.hpp"
#include "spaces/photo_enhancement.hpp"
#include "util/atomic_file.hpp"

namespace spaces {

namespace {

struct PhotoCell : app::PreparedCell {
  std::array<float, 12> p{};
};

class PhotoContent : public app::CellContent {
 public:
  explicit PhotoContent(std::shared_ptr<render::PhotoRenderer> renderer)
      : renderer_(std::move(renderer)) {}
  void upload(const app::PreparedCell& cell) override {
    p_ = static_cast<const PhotoCell&>(cell).p;
  }
  void draw(int width, int height, const app::CellLook& look) override {
    std::array<float, 12> p = p_;
    if (look.muted) p = {};  // "started from": the photo as it came
    renderer_->draw(p, width, height);
  }

 private:
  std::shared_ptr<render::PhotoRenderer> renderer_;
  std::array<float, 12> p_{};
};

// Box-filters the image down by an integer factor until no side exceeds `max_edge`.
Image shrink(const Image& in, int max_edge) {
  const int factor = std::max(1, (std::max(in.width, in.height) + max_edge - 1) / max_edge);
  if (factor == 1) return in;
  Image out;
  out.width = in.width / factor;
  out.height = in.height / factor;
  out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      for (int k = 0; k < 4; ++k) {
        unsigned sum = 0;
        for (int dy = 0; dy < factor; ++dy) {
          for (int dx = 0; dx < factor; ++dx) {
            sum +=
                in.rgba[(static_cast<std::size_t>(y * factor + dy) * in.width + x * factor + dx) *
                            4 +
                        k];
          }
        }
        out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4 + k] =
            static_cast<std::uint8_t>(sum / static_cast<unsigned>(factor * factor));
      }
    }
  }
  return out;
}

}  // namespace

PhotoSpace::PhotoSpace(Image image, std::string source)
    : image_(std::move(image)),
      texture_(shrink(image_, 2048)),
      source_(std::move(source)),
      distance_(std::make_shared<const PhotoDistance>(image_)),
      scale_(distance_->direction_scale()) {}

PhotoSpace::~PhotoSpace() = default;

std::unique_ptr<PhotoSpace> PhotoSpace::open(const app::SpaceSettings& settings) {
  if (settings.dimensions != kPhotoParameters) {
    throw std::runtime_error("a photo edit has 12 parameters, not " +
                             std::to_string(settings.dimensions));
  }
  Image image = settings.source.empty() ? default_photo() : load_image(settings.source);
  return std::make_unique<PhotoSpace>(std::move(image), settings.source);
}

app::SpaceSettings PhotoSpace::settings() const {
  return app::SpaceSettings{"photo", source_, kPhotoParameters};
}

std::string PhotoSpace::description() const {
  return "photo " + (source_.empty() ? std::string("(built-in landscape)") : source_) + ", " +
         std::to_string(image_.width) + "x" + std::to_string(image_.height) +
         ", 12 colour parameters";
}

std::string PhotoSpace::dimension_name(int i) const {
  return photo_parameter_name(i);
}

float PhotoSpace::preview_aspect() const {
  return static_cast<float>(image_.width) / static_cast<float>(image_.height);
}

std::shared_ptr<const app::PreparedCell> PhotoSpace::prepare(const Eigen::VectorXd& x,
                                                             bool details) const {
  auto cell = std::make_shared<PhotoCell>();
  cell->x = x;
  cell->p = photo_parameters(x);
  cell->has_details = details;  // the parameters are all there is to show
  return cell;
}

app::PairwiseDistance PhotoSpace::perceptual_distance() const {
  // The hook holds the distance itself, so a session kept for redo outlives the space.
  return [distance = distance_](const std::vector<Eigen::VectorXd>& xs) {
    return distance->pairwise(xs);
  };
}

app::ZoomPolicy PhotoSpace::zoom_policy(int /*cell_px*/) const {
  return photo_zoom_policy();
}

Eigen::VectorXd PhotoSpace::perceptual_scale() const {
  return scale_;
}

sps::Population PhotoSpace::population() const {
  return photo_population();
}

std::unique_ptr<app::CellContent> PhotoSpace::make_content() {
  if (!renderer_) {
    renderer_ =
        std::make_shared<render::PhotoRenderer>(texture_.width, texture_.height, texture_.rgba);
  }
  return std::make_unique<PhotoContent>(renderer_);
}

void PhotoSpace::draw_inspector(const app::PreparedCell& shown, const char* shown_label,
                                const app::PreparedCell* reference,
                                const char* reference_label) const {
  const auto& a = static_cast<const PhotoCell&>(shown);
  const auto* b = static_cast<const PhotoCell*>(reference);
  if (!ImGui::BeginTable("parameters", b != nullptr ? 4 : 2,
                         ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    return;
  }
  // The names ("highlights: magenta - green") are the long column; the numbers are short.
  ImGui::TableSetupColumn("(-100 .. +100)", ImGuiTableColumnFlags_WidthStretch, 3.0f);
  ImGui::TableSetupColumn(shown_label, ImGuiTableColumnFlags_WidthStretch, 1.0f);
  if (b != nullptr) {
    ImGui::TableSetupColumn(reference_label, ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("difference", ImGuiTableColumnFlags_WidthStretch, 1.0f);
  }
  ImGui::TableHeadersRow();
  for (int i = 0; i < kPhotoParameters; ++i) {
    const auto k = static_cast<std::size_t>(i);
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(photo_parameter_name(i).c_str());
    ImGui::TableSetColumnIndex(1);
    ImGui::Text("%+.0f", 100.0 * static_cast<double>(a.p[k]));
    if (b != nullptr) {
      ImGui::TableSetColumnIndex(2);
      ImGui::Text("%+.0f", 100.0 * static_cast<double>(b->p[k]));
      ImGui::TableSetColumnIndex(3);
      ImGui::Text("%+.0f", 100.0 * static_cast<double>(a.p[k] - b->p[k]));
    }
  }
  ImGui::EndTable();
}

std::string PhotoSpace::cell_summary(const app::PreparedCell& cell,
                                     const app::PreparedCell& reference) const {
  // The two parameters that differ most, on the window's -100 .. +100 scale.
  const auto& a = static_cast<const PhotoCell&>(cell);
  const auto& b = static_cast<const PhotoCell&>(reference);
  std::array<int, kPhotoParameters> order{};
  for (int i = 0; i < kPhotoParameters; ++i) order[static_cast<std::size_t>(i)] = i;
  const auto diff = [&](int i) {
    return 100.0 *
           static_cast<double>(a.p[static_cast<std::size_t>(i)] - b.p[static_cast<std::size_t>(i)]);
  };
  std::sort(order.begin(), order.end(),
            [&](int x, int y) { return std::abs(diff(x)) > std::abs(diff(y)); });
  std::string text;
  char item[64];
  for (int j = 0; j < 2; ++j) {
    const int i = order[static_cast<std::size_t>(j)];
    if (std::abs(diff(i)) < 0.5) break;
    std::snprintf(item, sizeof item, "%s%s %+.0f", text.empty() ? "" : ", ",
                  photo_parameter_name(i).c_str(), diff(i));
    text += item;
  }
  return text.empty() ? "about the same as the current best" : text;
}

std::string PhotoSpace::export_point(const Eigen::VectorXd& x,
                                     const std::filesystem::path& path) const {
  const auto p = photo_parameters(x);
  Image out = image_;
  enhance_image(out.rgba, p);
  const std::string bytes = encode_image(out, path);  // checks the extension first
  nlohmann::json j;
  j["format"] = "sequential-gallery-photo-edit";
  j["source"] = source_.empty() ? std::string("built-in landscape") : source_;
  j["image"] = path.filename().string();
  j["width"] = out.width;
  j["height"] = out.height;
  j["x"] = std::vector<double>(x.data(), x.data() + x.size());
  nlohmann::json named = nlohmann::json::object();
  for (int i = 0; i < kPhotoParameters; ++i) {
    named[photo_parameter_name(i)] = p[static_cast<std::size_t>(i)];
  }
  j["parameters"] = named;
  std::filesystem::path json_path = path;
  json_path.replace_extension(".json");
  util::write_file_atomically(path, bytes);
  util::write_file_atomically(json_path, j.dump(1));
  return std::filesystem::absolute(path).string() + " (" + std::to_string(out.width) + "x" +
         std::to_string(out.height) + ", " + std::to_string((bytes.size() + 512) / 1024) +
         " KiB) and " + json_path.filename().string();
}

}  // namespace spaces
