// Body shapes as a design space: x in [0,1]^K are a PCA body model's shape coefficients
// (beta = 6x - 3, +-3 standard deviations, as in the paper). Cells are bodies drawn with one
// shared orbit camera; the inspector shows height and girths; export writes glTF.
#pragma once

#include <memory>
#include <string>

#include "app/cell_visibility.hpp"
#include "app/design_space.hpp"
#include "body/body_model.hpp"
#include "spaces/body_framing.hpp"

namespace render {
class BodyRenderer;
}

namespace spaces {

// The population of a body model's shape space in search coordinates (standardized shape
// coefficients: N(0, 1) each), for sps::SearchOptions::population.
sps::Population body_population(int components);

// How the window's uncertainty planes for bodies are sized: the optimizer's extent and
// smallest side, and the choices' regions trusted with 8 choice temperatures of slack (body
// benchmark, 100 trials, mean gap at plane 10: a 5 mm person 7.54 -> 6.38 mm, the pixel
// person at 400 px 6.72 -> 6.05, at 230 px 7.53 -> 7.94 with the median 7.36 -> 7.28; 4
// temperatures helped the 5 mm person as much and cost the 230 px person more;
// docs/benchmarks.md). Used by BodySpace and by `simulate --function body`.
constexpr double kBodyChoiceRegionSlack = 8.0;
inline sps::UncertaintyPlaneSize body_uncertainty_size() {
  sps::UncertaintyPlaneSize size;
  size.region_slack = kBodyChoiceRegionSlack;
  return size;
}

// The smallest side of the window's uncertainty planes for bodies (half-diagonals, as
// sps::SearchOptions::uncertainty_min_side), for a person to whom cells closer than
// `look_alike_mm` (largest vertex distance, as the cells are framed) look alike: 8 of their
// thresholds in RMS mm (app::kLargestPerRmsDistance). A first grid's neighbours are a side
// apart and the fourth zoom level's about a third of it (0.7^3), so a side sized for a finer
// eye leaves a coarse eye's last clicks as guesses. Body benchmark (docs/benchmarks.md), median
// gap at plane 15, the 5 mm person (a 40 mm side against twice min_plane_length, 24 mm) on
// three sets of seeds (1000: 100 trials, 3000 and 5000: 200 each): 5.06 -> 4.53, 4.93 -> 4.77,
// 5.12 -> 4.87 mm; 30 mm changed nothing, 36-42 mm gained about as much as 40, 48 mm nothing.
// The pixel person at the default 230 px with close-ups (11 mm, a 30 mm side), mean gap at
// plane 10 on seeds 1000 and 3000 (100 trials each): 7.94 -> 7.87 and 8.07 -> 8.05 mm; framed
// whole (19 mm, 50 mm against 37): 10.06 -> 10.29 and 10.54 -> 9.80, at plane 15 8.61 -> 8.41
// and 8.32 -> 8.05; at 400 px with close-ups the bound (17 mm) is below the 24 mm.
constexpr double kBodyUncertaintySideThresholds = 8.0;
inline double body_uncertainty_min_side(double look_alike_mm) {
  return kBodyUncertaintySideThresholds * look_alike_mm / app::kLargestPerRmsDistance;
}

class BodySpace : public app::DesignSpace,
                  public app::SpacePerception,
                  public app::SpaceMeasurements {
 public:
  // `source`: the .npz it came from ("" = the embedded default model).
  BodySpace(body::Model model, std::string source);
  ~BodySpace() override;
  // Loads the model (components = settings.dimensions): a built-in model's name (female, male,
  // neutral; empty = neutral) or a file, as --model does. Throws body::ModelError naming the
  // file and the problem.
  static std::unique_ptr<BodySpace> open(const app::SpaceSettings& settings);

  app::SpaceSettings settings() const override;
  std::string description() const override;
  std::string source_label() const override;
  std::string dimension_name(int i) const override;
  std::string dimension_details(int i) const override;
  std::string cell_summary(const app::PreparedCell& cell,
                           const app::PreparedCell& reference) const override;
  bool uses_camera() const override { return true; }
  float preview_aspect() const override { return 260.0f / 320.0f; }  // an A-pose fits
  std::shared_ptr<const app::PreparedCell> prepare(const Eigen::VectorXd& x,
                                                   bool details) const override;
  std::unique_ptr<app::CellContent> make_content() override;
  void draw_inspector(const app::PreparedCell& shown, const char* shown_label,
                      const app::PreparedCell* reference,
                      const char* reference_label) const override;
  std::vector<std::pair<std::string, double>> numbers(const app::PreparedCell& cell) const override;
  std::string default_export_name() const override { return "body.glb"; }
  std::string export_hint() const override { return ".glb or .gltf"; }
  std::string export_point(const Eigen::VectorXd& x,
                           const std::filesystem::path& path) const override;

  const app::SpacePerception* perception() const override { return this; }
  const app::SpaceMeasurements* measurements() const override { return this; }

  // app::SpaceMeasurements
  std::vector<std::string> measurement_names() const override;
  std::shared_ptr<const app::ConstraintProjector> hold_projector(
      const std::vector<std::string>& holds, const Eigen::VectorXd& reference) const override;
  app::MeasurementPanelRequest draw_measurement_panel(
      const app::PreparedCell* best, const app::PreparedCell* start,
      const app::PreparedCell* hovered, const std::vector<std::string>& holds,
      app::MeasurementPanelState& state) const override;
  app::TargetSolve solve_targets(const std::vector<std::string>& targets,
                                 const Eigen::VectorXd& start,
                                 const std::vector<std::string>& held = {}) const override;

  // app::SpacePerception
  app::PairwiseDistance perceptual_distance() const override;
  app::GridFrame grid_frame(const std::vector<Eigen::VectorXd>& xs) const override;
  bool set_close_ups(bool on) override;
  bool close_ups() const override { return framed_->framing() == BodyFraming::kCloseUps; }
  app::ZoomPolicy zoom_policy(int cell_px) const override;
  double min_plane_length(int cell_px) const override;
  double choice_temperature(int cell_px) const override;
  // A person who cannot tell near neighbours apart at the cells' size: planes along where the
  // estimate of the body in mind is least certain (docs/benchmarks.md, the pixel person).
  sps::PlaneAxes plane_axes() const override { return sps::PlaneAxes::kTargetUncertainty; }
  sps::UncertaintyPlaneSize uncertainty_size() const override { return body_uncertainty_size(); }
  double uncertainty_min_side(int cell_px) const override;
  Eigen::VectorXd perceptual_scale() const override;
  // The RMS vertex distance's Gram matrix (body::ShapeDistance::direction_gram_mm2): a model's
  // components need not be orthogonal in vertex space (the built-in ones are turned so that
  // component 1 carries stature and component 2 mass).
  Eigen::MatrixXd perceptual_metric() const override;
  sps::Population population() const override;

  const body::Model& model() const { return model_; }

 private:
  // The largest vertex distance (mm) that 2 px show in a typical cell of `cell_px` pixels in
  // the current framing (cell_px > 0): what min_plane_length and uncertainty_min_side follow.
  double framed_look_alike_mm(int cell_px) const;

  body::Model model_;
  std::string source_;
  // The same model for projectors and solves that may outlive this space (a session in the
  // redo stack); made on first use.
  mutable std::shared_ptr<const body::Model> shared_model_;
  // The grids' framing and distances as seen, shared with the session's hook.
  std::shared_ptr<const FramedBodies> framed_;
  std::shared_ptr<render::BodyRenderer> renderer_;  // made on the GL thread, shared by cells
  std::vector<float> eye_tints_;                    // the cells' eye colours (body_scene.hpp)
  // What each component does to the body, measured the first time a label is asked for.
  struct ComponentEffect {
    std::string label, details;
  };
  mutable std::vector<ComponentEffect> effects_;
  const ComponentEffect& effect(int i) const;
};

}  // namespace spaces
