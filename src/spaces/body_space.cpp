#include "spaces/body_space.hpp"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "app/cell_visibility.hpp"
#include "body/gltf_export.hpp"
#include "body/measurement_solve.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "render/body_renderer.hpp"
#include "render/mesh_gpu.hpp"
#include "spaces/body_holds.hpp"
#include "spaces/body_scene.hpp"

namespace spaces {

namespace {

struct BodyCell : app::PreparedCell {
  body::BodyMesh mesh;
  std::optional<body::Measurements> measurements;
};

class BodyContent : public app::CellContent {
 public:
  BodyContent(std::shared_ptr<render::BodyRenderer> renderer, const body::Model& model,
              const std::vector<float>& tints)
      : renderer_(std::move(renderer)), model_(&model), tints_(&tints) {}

  void upload(const app::PreparedCell& cell) override {
    show_mesh(gpu_, *model_, static_cast<const BodyCell&>(cell).mesh, *tints_);
  }

  void draw(int width, int height, const app::CellLook& look) override {
    render::BodyStyle style = cell_style();
    if (look.muted) style.albedo = {0.62f, 0.66f, 0.72f};
    static const render::Camera front;
    renderer_->draw(gpu_, look.camera != nullptr ? *look.camera : front, width, height, style);
  }

 private:
  std::shared_ptr<render::BodyRenderer> renderer_;
  // The space outlives its cells' uploads (same model).
  const body::Model* model_;
  const std::vector<float>* tints_;
  render::MeshGpu gpu_;
};

}  // namespace

BodySpace::BodySpace(body::Model model, std::string source)
    : model_(std::move(model)),
      source_(std::move(source)),
      framed_(std::make_shared<const FramedBodies>(model_, BodyFraming::kCloseUps)),
      eye_tints_(eye_tints(model_)) {}

std::vector<std::string> BodySpace::measurement_names() const {
  std::vector<std::string> names;
  for (const auto& k : body::measurement_kinds()) names.emplace_back(k.name);
  return names;
}

namespace {

std::vector<body::MeasurementTarget> parse_all(const std::vector<std::string>& texts) {
  std::vector<body::MeasurementTarget> targets;
  for (const auto& text : texts) targets.push_back(body::parse_target(text, true));
  return targets;
}

}  // namespace

std::shared_ptr<const app::ConstraintProjector> BodySpace::hold_projector(
    const std::vector<std::string>& holds, const Eigen::VectorXd& reference) const {
  if (!shared_model_) shared_model_ = std::make_shared<const body::Model>(model_);
  return make_body_holds(shared_model_, holds, reference);
}

app::TargetSolve BodySpace::solve_targets(const std::vector<std::string>& texts,
                                          const Eigen::VectorXd& start,
                                          const std::vector<std::string>& held) const {
  if (!shared_model_) shared_model_ = std::make_shared<const body::Model>(model_);
  std::vector<body::MeasurementTarget> holds;
  for (const auto& text : held) holds.push_back(body::parse_target(text, false));
  const body::MeasurementConstraints constraints(shared_model_,
                                                 body::targets_with_holds(parse_all(texts), holds));
  const auto result = constraints.solve(start);
  return {result.x, result.reached, result.message};
}

app::PairwiseDistance BodySpace::perceptual_distance() const {
  return seen_body_distance(framed_);
}

bool BodySpace::set_close_ups(bool on) {
  // A new object: sessions in the redo stack keep the hook they were made with.
  if (on != close_ups()) {
    framed_ = std::make_shared<const FramedBodies>(
        model_, on ? BodyFraming::kCloseUps : BodyFraming::kWholeBody);
  }
  return on;
}

app::GridFrame BodySpace::grid_frame(const std::vector<Eigen::VectorXd>& xs) const {
  return framed_->grid_frame(xs);
}

app::ZoomPolicy BodySpace::zoom_policy(int cell_px) const {
  // Neighbouring cells must differ by what the person can see in a cell of this size (at the
  // default window's 230 px, 2 px are 19 mm); the session's default until the size is known.
  return cell_px > 0 ? app::zoom_policy_for_cells(cell_px) : app::ZoomPolicy{};
}

double BodySpace::framed_look_alike_mm(int cell_px) const {
  return app::look_alike_mm(cell_px, app::kDefaultJndPx) * framed_->typical_scale();
}

double BodySpace::min_plane_length(int cell_px) const {
  // A plane shorter than what a pixel-limited person sees shows look-alike cells however its
  // first grid is widened (the benchmark's pixel person has the same rule): at 230 px, 19 mm
  // on the whole body, 11 mm in a typical close-up.
  return cell_px > 0
             ? std::max(sps::SearchOptions{}.min_plane_length, framed_look_alike_mm(cell_px))
             : 0.0;
}

double BodySpace::uncertainty_min_side(int cell_px) const {
  return cell_px > 0 ? body_uncertainty_min_side(framed_look_alike_mm(cell_px)) : 0.0;
}

double BodySpace::choice_temperature(int cell_px) const {
  return cell_px > 0 ? app::choice_temperature_for_cells(cell_px) : 0.0;
}

Eigen::VectorXd BodySpace::perceptual_scale() const {
  return framed_->distance().direction_rms_mm();
}

Eigen::MatrixXd BodySpace::perceptual_metric() const {
  return framed_->distance().direction_gram_mm2();
}

sps::Population body_population(int components) {
  // SMPL-family shape coefficients are standardized: beta ~ N(0, 1) over the people the model
  // was built from, and a search point maps beta = 6x - 3 (+-3 SD), so x ~ N(1/2, (1/6)^2).
  const auto k = static_cast<Eigen::Index>(components);
  return {Eigen::VectorXd::Constant(k, 0.5), Eigen::VectorXd::Constant(k, 1.0 / 6.0),
          Eigen::MatrixXd()};
}

sps::Population BodySpace::population() const {
  return body_population(framed_->distance().dims());
}

BodySpace::~BodySpace() = default;

std::unique_ptr<BodySpace> BodySpace::open(const app::SpaceSettings& settings) {
  if (settings.dimensions < 1) throw body::ModelError("a body space needs at least 1 component");
  // SMPL's own .pkl holds Python objects; say how to convert it instead of "not a zip archive".
  std::string ext = std::filesystem::path(settings.source).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (ext == ".pkl" && !body::is_builtin_model_name(settings.source)) {
    throw body::ModelError(
        settings.source +
        ": a .pkl model cannot be read directly; convert it once with "
        "`python3 tools/smpl_pkl_to_npz.py FILE.pkl FILE.npz` and open the .npz");
  }
  // resolve_model, as --model: a built-in name always means the built-in model, even when the
  // current folder holds a file or folder of that name.
  body::Model model = body::resolve_model(settings.source, settings.dimensions);
  return std::make_unique<BodySpace>(std::move(model), settings.source);
}

app::SpaceSettings BodySpace::settings() const {
  return app::SpaceSettings{"body", source_, model_.component_count()};
}

std::string BodySpace::description() const {
  if (source_.empty() || body::is_builtin_model_name(source_)) {
    return "body model " + source_label() + ", " + std::to_string(model_.component_count()) +
           " components";
  }
  return "body model " + source_ + " \"" + model_.name + "\", " +
         std::to_string(model_.component_count()) + " components";
}

std::string BodySpace::source_label() const {
  if (source_.empty()) return "neutral (built-in)";
  if (body::is_builtin_model_name(source_)) return source_ + " (built-in)";
  return std::filesystem::path(source_).filename().string();
}

namespace {

// A measurement's words for more and less of it, and the spread it is judged against (about
// one SD of adults, ANSUR II both sexes pooled; metres, kg), so that a 1 cm change of the
// shoulders counts as much as a 5 cm change of the waist.
struct EffectWords {
  const char* name;
  const char* more;
  const char* less;
  double spread;
};
constexpr EffectWords kEffectWords[] = {
    {"height", "taller", "shorter", 0.090},
    {"mass", "heavier", "lighter", 15.7},
    {"chest", "fuller chest", "smaller chest", 0.101},
    {"waist", "thicker waist", "slimmer waist", 0.114},
    {"hips", "wider hips", "narrower hips", 0.076},
    {"shoulder_width", "broader shoulders", "narrower shoulders", 0.030},
    {"inseam", "longer legs", "shorter legs", 0.055},
    {"arm_length", "longer arms", "shorter arms", 0.038},
};

// One measurement's change between two bodies, and how visible it is (in its spreads).
struct Change {
  const EffectWords* words;
  double delta, score;
};

// (a - b) * scale for every measurement that has words, the most visible first.
std::vector<Change> ranked_changes(const body::Measurements& a, const body::Measurements& b,
                                   double scale) {
  std::vector<Change> changes;
  for (const auto& w : kEffectWords) {
    const auto* kind = body::find_measurement(w.name);
    const double d = scale * (a.*(kind->field) - b.*(kind->field));
    if (std::isfinite(d)) changes.push_back({&w, d, std::abs(d) / w.spread});
  }
  std::sort(changes.begin(), changes.end(),
            [](const Change& x, const Change& y) { return x.score > y.score; });
  return changes;
}

}  // namespace

const BodySpace::ComponentEffect& BodySpace::effect(int i) const {
  if (effects_.empty()) {
    // Each component from -1 to +1 SD, the others at the mean: the difference of the tool's
    // measurements (the torso girths and the joint lengths; not the limb slices, to keep this
    // to ~100 ms once).
    const int k = model_.component_count();
    effects_.resize(static_cast<std::size_t>(k));
    constexpr unsigned kBands = body::kChestBand | body::kWaistBand | body::kHipsBand;
    for (int c = 0; c < k; ++c) {
      Eigen::VectorXf betas = Eigen::VectorXf::Zero(k);
      betas[c] = 1.0f;
      const body::Measurements up = body::measure(model_, betas, true, kBands);
      betas[c] = -1.0f;
      const body::Measurements down = body::measure(model_, betas, true, kBands);
      const std::vector<Change> changes = ranked_changes(up, down, 0.5);  // per SD
      ComponentEffect& e = effects_[static_cast<std::size_t>(c)];
      e.label = std::to_string(c + 1) + ":";
      bool height_named = false;
      // The two largest effects in words, the first with its size (components that change
      // the same things differ in how much).
      for (std::size_t j = 0; j < changes.size() && j < 2; ++j) {
        e.label += std::string(j == 0 ? " " : ", ") +
                   (changes[j].delta >= 0.0 ? changes[j].words->more : changes[j].words->less);
        if (j == 0) {
          const auto* kind = body::find_measurement(changes[j].words->name);
          e.label += " " + body::format_measurement(kind->quantity, std::abs(changes[j].delta),
                                                    body::Units::kMetric);
        }
        height_named = height_named || std::string(changes[j].words->name) == "height";
      }
      const auto height = std::find_if(changes.begin(), changes.end(), [](const Change& ch) {
        return std::string(ch.words->name) == "height";
      });
      // Two components that read alike are told apart by their third effect.
      const auto words = [](const std::string& label) { return label.substr(label.find(':')); };
      const bool repeated =
          std::any_of(effects_.begin(), effects_.begin() + c,
                      [&](const ComponentEffect& o) { return words(o.label) == words(e.label); });
      const std::string third =
          changes.size() > 2 ? ", " + std::string(changes[2].delta >= 0.0 ? changes[2].words->more
                                                                          : changes[2].words->less)
                             : std::string();
      if (repeated && !third.empty() && e.label.size() + third.size() <= 46) {
        e.label += third;
      } else if (!height_named && height != changes.end() && std::abs(height->delta) < 0.01 &&
                 e.label.size() < 34) {
        e.label += ", same height";
      }
      e.details = "Component " + std::to_string(c + 1);
      if (c < model_.variance_share.size()) {
        char share[64];
        std::snprintf(share, sizeof share, " (%.0f%% of the shape variance)",
                      100.0 * static_cast<double>(model_.variance_share[c]));
        e.details += share;
      }
      e.details += "; per standard deviation to the right:";
      for (const auto& ch : changes) {
        const auto* kind = body::find_measurement(ch.words->name);
        e.details += "\n  " + std::string(kind->label) + " " +
                     body::format_difference(kind->quantity, ch.delta, body::Units::kMetric);
      }
    }
  }
  static const ComponentEffect none{};
  return i >= 0 && i < static_cast<int>(effects_.size()) ? effects_[static_cast<std::size_t>(i)]
                                                         : none;
}

std::string BodySpace::cell_summary(const app::PreparedCell& cell,
                                    const app::PreparedCell& reference) const {
  const auto& a = static_cast<const BodyCell&>(cell);
  const auto& b = static_cast<const BodyCell&>(reference);
  if (!a.measurements || !b.measurements) return {};
  const std::vector<Change> changes = ranked_changes(*a.measurements, *b.measurements, 1.0);
  std::string text;
  for (std::size_t j = 0; j < changes.size() && j < 2; ++j) {
    if (changes[j].score < 0.02) break;  // under about 2 mm or 0.3 kg: no change to speak of
    const auto* kind = body::find_measurement(changes[j].words->name);
    text +=
        (text.empty() ? "" : ", ") +
        std::string(changes[j].delta >= 0.0 ? changes[j].words->more : changes[j].words->less) +
        " " +
        body::format_measurement(kind->quantity, std::abs(changes[j].delta), body::Units::kMetric);
  }
  return text.empty() ? "about the same as the current best" : text;
}

std::string BodySpace::dimension_name(int i) const {
  const std::string& label = effect(i).label;
  return label.empty() ? "shape " + std::to_string(i + 1) : label;
}

std::string BodySpace::dimension_details(int i) const {
  return effect(i).details;
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
  return std::make_unique<BodyContent>(renderer_, model_, eye_tints_);
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
  for (const auto& k : body::measurement_kinds()) {
    const double va = ma.*k.field, vb = mb.*k.field;
    const auto metric = body::Units::kMetric;
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(k.label);
    ImGui::TableSetColumnIndex(1);
    ImGui::TextUnformatted(a.measurements ? body::format_measurement(k.quantity, va, metric).c_str()
                                          : "...");
    if (b != nullptr) {
      ImGui::TableSetColumnIndex(2);
      ImGui::TextUnformatted(
          b->measurements ? body::format_measurement(k.quantity, vb, metric).c_str() : "...");
      ImGui::TableSetColumnIndex(3);
      if (a.measurements && b->measurements) {
        ImGui::TextUnformatted(body::format_difference(k.quantity, va - vb, metric).c_str());
      }
    }
  }
  ImGui::EndTable();
}

app::MeasurementPanelRequest BodySpace::draw_measurement_panel(
    const app::PreparedCell* best, const app::PreparedCell* start, const app::PreparedCell* hovered,
    const std::vector<std::string>& holds, app::MeasurementPanelState& state) const {
  app::MeasurementPanelRequest request;
  const auto& kinds = body::measurement_kinds();
  state.target_text.resize(kinds.size());
  const auto units = state.imperial ? body::Units::kImperial : body::Units::kMetric;
  ImGui::TextUnformatted("Units:");
  ImGui::SameLine();
  if (ImGui::RadioButton("metric", !state.imperial)) state.imperial = false;
  ImGui::SameLine();
  if (ImGui::RadioButton("imperial", state.imperial)) state.imperial = true;
  ImGui::SameLine();
  ImGui::Checkbox("limbs and neck", &state.all_rows);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Also show the neck, deltoid breadth, upper arm, thigh and calf");
  }
  const auto held_name = [](const std::string& text) { return text.substr(0, text.find('=')); };
  const BodyCell* columns[3] = {static_cast<const BodyCell*>(best),
                                static_cast<const BodyCell*>(start),
                                static_cast<const BodyCell*>(hovered)};
  if (ImGui::BeginTable(
          "measurement panel", 6,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("current");
    ImGui::TableSetupColumn("start");
    ImGui::TableSetupColumn("hovered");
    ImGui::TableSetupColumn("hold");
    ImGui::TableSetupColumn("target", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      const auto& k = kinds[i];
      // The measures across the limbs are rows on request, so the side panel stays short;
      // one that is held or has a typed target is always shown.
      const bool secondary =
          (body::girth_band(k) & (body::kNeckBand | body::kArmBand | body::kLegBand)) != 0;
      const bool in_use = !state.target_text[i].empty() ||
                          std::any_of(holds.begin(), holds.end(),
                                      [&](const std::string& h) { return held_name(h) == k.name; });
      if (secondary && !state.all_rows && !in_use) continue;
      ImGui::PushID(static_cast<int>(i));
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(k.label);
      for (int c = 0; c < 3; ++c) {
        ImGui::TableSetColumnIndex(c + 1);
        const BodyCell* cell = columns[c];
        if (cell == nullptr) continue;
        ImGui::TextUnformatted(
            cell->measurements
                ? body::format_measurement(k.quantity, (*cell->measurements).*k.field, units)
                      .c_str()
                : "...");
      }
      ImGui::TableSetColumnIndex(4);
      bool held = std::any_of(holds.begin(), holds.end(),
                              [&](const std::string& h) { return held_name(h) == k.name; });
      if (ImGui::Checkbox("##hold", &held)) {
        std::vector<std::string> next;
        for (const auto& h : holds) {
          if (held_name(h) != k.name) next.push_back(h);
        }
        if (held) next.emplace_back(k.name);
        request.holds = next;
      }
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Hold %s: every cell keeps the current best's value", k.label);
      }
      ImGui::TableSetColumnIndex(5);
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%s", state.target_text[i].c_str());
      ImGui::SetNextItemWidth(-1.0f);
      if (ImGui::InputTextWithHint("##target",
                                   state.imperial ? k.example_imperial : k.example_metric, buffer,
                                   sizeof buffer)) {
        state.target_text[i] = buffer;
      }
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  std::vector<std::string> targets;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    std::string text = state.target_text[i];
    text.erase(std::remove(text.begin(), text.end(), ' '), text.end());
    if (!text.empty()) targets.push_back(std::string(kinds[i].name) + "=" + text);
  }
  ImGui::BeginDisabled(targets.empty());
  if (ImGui::Button("Go")) request.targets = targets;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("the nearest body meeting the typed targets");
  return request;
}

std::vector<std::pair<std::string, double>> BodySpace::numbers(
    const app::PreparedCell& cell) const {
  const auto& b = static_cast<const BodyCell&>(cell);
  if (!b.measurements) return {};
  std::vector<std::pair<std::string, double>> out;
  for (const auto& k : body::measurement_kinds()) {
    const char* unit = k.quantity == body::Quantity::kLength ? "_m"
                       : k.quantity == body::Quantity::kMass ? "_kg"
                                                             : "";
    out.emplace_back(std::string(k.name) + unit, (*b.measurements).*k.field);
  }
  return out;
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
