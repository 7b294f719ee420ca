#include "spaces/body_space.hpp"

#include <imgui.h>

#include <cstdio>
#include <optional>

#include "body/gltf_export.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "render/body_renderer.hpp"
#include "render/mesh_gpu.hpp"
#include "spaces/body_scene.hpp"

namespace spaces {

namespace {

struct BodyCell : app::PreparedCell {
  body::BodyMesh mesh;
  std::optional<body::Measurements> measurements;
};

class BodyContent : public app::CellContent {
 public:
  BodyContent(std::shared_ptr<render::BodyRenderer> renderer, const body::Model& model)
      : renderer_(std::move(renderer)), faces_(&model.faces) {}

  void upload(const app::PreparedCell& cell) override {
    const auto& b = static_cast<const BodyCell&>(cell);
    const int vertices = static_cast<int>(b.mesh.vertices.rows());
    if (gpu_.empty() || gpu_.vertex_count() != vertices) {
      gpu_.upload(b.mesh.vertices.data(), b.mesh.normals.data(), vertices, faces_->data(),
                  static_cast<int>(faces_->size()));
    } else {
      gpu_.update(b.mesh.vertices.data(), b.mesh.normals.data(), vertices);
    }
  }

  void draw(int width, int height, const app::CellLook& look) override {
    render::BodyStyle style = cell_style();
    if (look.muted) style.albedo = {0.62f, 0.66f, 0.72f};
    static const render::Camera front;
    renderer_->draw(gpu_, look.camera != nullptr ? *look.camera : front, width, height, style);
  }

 private:
  std::shared_ptr<render::BodyRenderer> renderer_;
  const body::Faces* faces_;  // the space outlives its cells' uploads (same model)
  render::MeshGpu gpu_;
};

std::string centimetres(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f cm", m * 100.0);
  return text;
}

std::string signed_centimetres(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f cm", m * 100.0);
  return text;
}

}  // namespace

BodySpace::BodySpace(body::Model model, std::string source)
    : model_(std::move(model)),
      source_(std::move(source)),
      distance_(std::make_shared<const body::ShapeDistance>(model_)) {}

app::PairwiseDistance BodySpace::perceptual_distance() const {
  // The hook holds the distance itself, so a session copied into the redo stack stays valid
  // after the space is replaced.
  return [distance = distance_](const std::vector<Eigen::VectorXd>& xs) {
    return distance->pairwise_max_mm(xs);
  };
}

Eigen::VectorXd BodySpace::perceptual_scale() const {
  return distance_->direction_rms_mm();
}

BodySpace::~BodySpace() = default;

std::unique_ptr<BodySpace> BodySpace::open(const app::SpaceSettings& settings) {
  if (settings.dimensions < 1) throw body::ModelError("a body space needs at least 1 component");
  body::Model model = settings.source.empty()
                          ? body::load_default_model(settings.dimensions)
                          : body::load_model(settings.source, settings.dimensions);
  return std::make_unique<BodySpace>(std::move(model), settings.source);
}

app::SpaceSettings BodySpace::settings() const {
  return app::SpaceSettings{"body", source_, model_.component_count()};
}

std::string BodySpace::description() const {
  return "body model " + (source_.empty() ? std::string("(default)") : source_) + " \"" +
         model_.name + "\", " + std::to_string(model_.component_count()) + " components";
}

std::string BodySpace::dimension_name(int i) const {
  std::string name = "shape " + std::to_string(i + 1);
  if (i >= 0 && i < model_.variance_share.size()) {
    char share[48];
    std::snprintf(share, sizeof share, " (%.0f%% var.)",
                  100.0 * static_cast<double>(model_.variance_share[i]));
    name += share;
  }
  return name;
}

std::shared_ptr<const app::PreparedCell> BodySpace::prepare(const Eigen::VectorXd& x,
                                                            bool details) const {
  auto cell = std::make_shared<BodyCell>();
  cell->x = x;
  cell->mesh = body_at(model_, x);
  if (details) {
    cell->measurements = body::measure(model_, cell->mesh);
    cell->has_details = true;
  }
  return cell;
}

std::unique_ptr<app::CellContent> BodySpace::make_content() {
  if (!renderer_) renderer_ = std::make_shared<render::BodyRenderer>();
  return std::make_unique<BodyContent>(renderer_, model_);
}

void BodySpace::draw_inspector(const app::PreparedCell& shown, const char* shown_label,
                               const app::PreparedCell* reference,
                               const char* reference_label) const {
  const auto& a = static_cast<const BodyCell&>(shown);
  const auto* b = static_cast<const BodyCell*>(reference);
  const int columns = b != nullptr ? 4 : 2;
  if (!ImGui::BeginTable("measurements", columns,
                         ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    return;
  }
  ImGui::TableSetupColumn("");
  ImGui::TableSetupColumn(shown_label);
  if (b != nullptr) {
    ImGui::TableSetupColumn(reference_label);
    ImGui::TableSetupColumn("difference");
  }
  ImGui::TableHeadersRow();
  const body::Measurements ma = a.measurements.value_or(body::Measurements{});
  const body::Measurements mb =
      b != nullptr ? b->measurements.value_or(body::Measurements{}) : body::Measurements{};
  const struct {
    const char* name;
    double a, b;
  } rows[] = {{"Height", ma.height, mb.height},
              {"Chest", ma.chest, mb.chest},
              {"Waist", ma.waist, mb.waist},
              {"Hips", ma.hips, mb.hips}};
  for (const auto& r : rows) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(r.name);
    ImGui::TableSetColumnIndex(1);
    ImGui::TextUnformatted(a.measurements ? centimetres(r.a).c_str() : "...");
    if (b != nullptr) {
      ImGui::TableSetColumnIndex(2);
      ImGui::TextUnformatted(b->measurements ? centimetres(r.b).c_str() : "...");
      ImGui::TableSetColumnIndex(3);
      if (a.measurements && b->measurements) {
        ImGui::TextUnformatted(signed_centimetres(r.a - r.b).c_str());
      }
    }
  }
  ImGui::EndTable();
}

std::vector<std::pair<std::string, double>> BodySpace::numbers(
    const app::PreparedCell& cell) const {
  const auto& b = static_cast<const BodyCell&>(cell);
  if (!b.measurements) return {};
  return {{"height_m", b.measurements->height},
          {"chest_m", b.measurements->chest},
          {"waist_m", b.measurements->waist},
          {"hips_m", b.measurements->hips}};
}

std::string BodySpace::export_point(const Eigen::VectorXd& x,
                                    const std::filesystem::path& path) const {
  body::export_gltf(model_, body::betas_from_unit(x), path);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  std::string text = std::filesystem::absolute(path).string();
  if (!ec) text += " (" + std::to_string((bytes + 512) / 1024) + " KiB)";
  return text;
}

}  // namespace spaces
