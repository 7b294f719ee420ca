// Photo colour enhancement as a design space (the paper's first application): x in [0,1]^12
// are brightness, contrast, saturation and the colour balance of shadows, midtones and
// highlights (x = 0.5 leaves the photo unchanged). Cells are the photo drawn through a
// fragment shader; export writes the enhanced full-resolution image and its parameters.
#pragma once

#include <memory>
#include <string>

#include "app/design_space.hpp"
#include "spaces/photo_image.hpp"
#include "spaces/photo_perception.hpp"

namespace render {
class PhotoRenderer;
}

namespace spaces {

class PhotoSpace : public app::DesignSpace, public app::SpacePerception {
 public:
  // `source`: the file it came from ("" = the built-in picture).
  PhotoSpace(Image image, std::string source);
  ~PhotoSpace() override;
  static std::unique_ptr<PhotoSpace> open(const app::SpaceSettings& settings);

  app::SpaceSettings settings() const override;
  std::string description() const override;
  std::string dimension_name(int i) const override;
  bool uses_camera() const override { return false; }
  float preview_aspect() const override;
  std::shared_ptr<const app::PreparedCell> prepare(const Eigen::VectorXd& x,
                                                   bool details) const override;
  std::unique_ptr<app::CellContent> make_content() override;
  std::string cell_summary(const app::PreparedCell& cell,
                           const app::PreparedCell& reference) const override;
  void draw_inspector(const app::PreparedCell& shown, const char* shown_label,
                      const app::PreparedCell* reference,
                      const char* reference_label) const override;
  const app::SpacePerception* perception() const override { return this; }
  // app::SpacePerception. Mean CIEDE2000 between the edited pictures (spaces/photo_perception.hpp),
  // in the slots where a body space gives millimetres.
  app::PairwiseDistance perceptual_distance() const override;
  // A picture fills its cell whatever the edit.
  app::GridFrame grid_frame(const std::vector<Eigen::VectorXd>& /*xs*/) const override {
    return {};
  }
  app::ZoomPolicy zoom_policy(int cell_px) const override;
  Eigen::VectorXd perceptual_scale() const override;
  double min_plane_length(int /*cell_px*/) const override { return kPhotoMinPlaneDeltaE; }
  // A picture's differences do not depend on the cell size here: the optimizer's default.
  double choice_temperature(int /*cell_px*/) const override { return 0.0; }
  sps::Population population() const override;
  sps::PlaneAxes plane_axes() const override { return sps::PlaneAxes::kTargetUncertainty; }
  sps::UncertaintyPlaneSize uncertainty_size() const override { return photo_uncertainty_size(); }
  std::string default_export_name() const override { return "photo.png"; }
  std::string export_hint() const override { return ".png or .jpg, plus a .json of parameters"; }
  std::string export_point(const Eigen::VectorXd& x,
                           const std::filesystem::path& path) const override;

  const Image& image() const { return image_; }

 private:
  Image image_;    // full resolution (exports)
  Image texture_;  // at most 2048 pixels a side (cells)
  std::string source_;
  std::shared_ptr<const PhotoDistance> distance_;  // shared with the sessions' hooks
  Eigen::VectorXd scale_;                          // distance_->direction_scale()
  std::shared_ptr<render::PhotoRenderer> renderer_;
};

}  // namespace spaces
