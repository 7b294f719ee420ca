// The seam between the gallery and what it designs. The gallery (controller, view, window)
// knows points x in [0,1]^n and cells that show them; a DesignSpace knows what a point means:
// a body shape (BodySpace), a photo edit (PhotoSpace), ... It names the dimensions, prepares
// a cell on the CPU (safe off the GL thread), draws a prepared cell into the bound cell
// framebuffer, shows an inspector for a cell and exports a point to a file. What only some
// spaces have comes as facets: what a person can see of a change (SpacePerception) and
// measurements to hold or aim for (SpaceMeasurements).
//
// This header holds no GL and no ImGui; implementations live in src/spaces/.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "app/cell_visibility.hpp"
#include "app/constraint_projector.hpp"
#include "app/session.hpp"
#include "render/camera.hpp"

namespace app {

// What a session stores about its space (in place of a body-specific model path).
struct SpaceSettings {
  std::string kind;    // a kind of the catalogue (app/space_catalogue.hpp); empty: its default
  std::string source;  // the kind's file (a model, a photo); empty = its built-in default
  int dimensions = 0;  // dimensions explored; 0: the kind's default
};

// A point made ready for drawing on the CPU: a body's mesh, a photo edit's parameters...
// Immutable once made, so it may be made on any thread and shared.
class PreparedCell {
 public:
  virtual ~PreparedCell() = default;
  Eigen::VectorXd x;
  bool has_details = false;  // e.g. a body's measurements (costly; previews and hover only)
};

// How a cell is drawn. Spaces without a 3D view ignore the camera.
struct CellLook {
  const render::Camera* camera = nullptr;
  bool muted = false;  // the "started from" preview
};

// The GPU side of one cell (GL thread only).
class CellContent {
 public:
  virtual ~CellContent() = default;
  virtual void upload(const PreparedCell& cell) = 0;
  // Draws into the bound framebuffer over width x height pixels.
  virtual void draw(int width, int height, const CellLook& look) = 0;
};

// Where a target solve ended.
struct TargetSolve {
  Eigen::VectorXd x;
  bool reached = false;
  std::string message;  // what was reached, or the nearest reachable values
};

// The window's measurements panel: what the view keeps between frames.
struct MeasurementPanelState {
  bool imperial = false;
  bool all_rows = false;  // also the secondary measurements (a body's limbs and neck)
  std::vector<std::string> target_text;  // typed targets, one per measurement_names()
};
// What the user asked for in the panel this frame.
struct MeasurementPanelRequest {
  std::optional<std::vector<std::string>> holds;    // the new set of holds (a toggle changed)
  std::optional<std::vector<std::string>> targets;  // "Go" with these "name=value" targets
};

// What a person can see of a change, for the zoom and the optimizer: how different the cells
// of some points look (entry (i, j) in mm, largest difference), so the session never shows a
// grid of look-alikes, and how much each coordinate changes a cell over its range (mm), so the
// optimizer does not explore invisible directions as if they mattered. The window installs
// them on every session, exactly as `simulate --function body` does. A space without one
// zooms by the paper's fixed factor.
class SpacePerception {
 public:
  virtual ~SpacePerception() = default;
  // The distance as the grid shows it: a space that frames each grid (grid_frame) reports a
  // grid's differences as they look in that framing, in units of its default framing.
  virtual PairwiseDistance perceptual_distance() const = 0;
  // How a grid of these points is framed: {1, 0} = the cells' default camera; else the camera
  // scaled by s about a height (render::Camera::scaled_about_height), everything 1/s larger.
  virtual GridFrame grid_frame(const std::vector<Eigen::VectorXd>& xs) const = 0;
  // How the zoom adapts when the cells are `cell_px` pixels high (0: not known yet): the
  // threshold under which two cells look alike follows from what a pixel shows.
  virtual ZoomPolicy zoom_policy(int cell_px) const = 0;
  // Empty: no per-coordinate scale.
  virtual Eigen::VectorXd perceptual_scale() const = 0;
  // With perceptual_scale(): empty where the coordinates are seen independently, else the full
  // metric whose diagonal is the scale squared (sps::SearchOptions::perceptual_metric).
  virtual Eigen::MatrixXd perceptual_metric() const { return {}; }
  // With perceptual_scale(): the smallest length of a plane's sides in its units when the
  // cells are `cell_px` pixels high (0: not known yet), so that a grid can hold cells that all
  // look different; 0 keeps the optimizer's default (sps::SearchOptions::min_plane_length).
  virtual double min_plane_length(int cell_px) const = 0;
  // With perceptual_scale() and population(): how noisy a person's choices are, in its units,
  // when the cells are `cell_px` pixels high (0: not known yet); 0 keeps the optimizer's
  // default (sps::SearchOptions::choice_temperature_mm).
  virtual double choice_temperature(int cell_px) const = 0;
  // With population(): what the planes' axes follow for a person in front of the window
  // (sps::SearchOptions::plane_axes).
  virtual sps::PlaneAxes plane_axes() const { return sps::PlaneAxes::kExpectedImprovement; }
  // With uncertainty planes: their half-diagonals in standard deviations of the estimate and
  // their smallest length in units of min_plane_length (sps::SearchOptions::
  // uncertainty_extent, uncertainty_min_lengths).
  virtual sps::UncertaintyPlaneSize uncertainty_size() const { return {}; }
  // With uncertainty planes: the smallest side a person needs to tell a deep zoom level's
  // cells apart when they are `cell_px` pixels high, in the perceptual scale's units
  // (sps::SearchOptions::uncertainty_min_side); 0: not known yet, or no bound beyond
  // min_plane_length.
  virtual double uncertainty_min_side(int /*cell_px*/) const { return 0.0; }
  // Where designs typically lie in the search box and how far they spread (a body model's
  // population); empty where unknown.
  virtual sps::Population population() const = 0;
};

// Named measurements a search may hold or aim for (a body's "height", "mass", ...), and the
// window's panel that shows them.
class SpaceMeasurements {
 public:
  virtual ~SpaceMeasurements() = default;
  virtual std::vector<std::string> measurement_names() const = 0;
  // Holds "name" or "name=value" (the value in SI or with a unit, "180cm"; a bare name holds
  // the value of the body at `reference`). Throws std::invalid_argument with a message for
  // the user (unknown name, bad value, a measurement this model lacks).
  virtual std::shared_ptr<const ConstraintProjector> hold_projector(
      const std::vector<std::string>& holds, const Eigen::VectorXd& reference) const = 0;
  // The point nearest to `start` meeting "name=value" targets (smallest change of x) that also
  // keeps the `held` values ("name=value", as hold_projector() takes them; bare names are
  // skipped). Throws std::invalid_argument as hold_projector() does, and when a target
  // contradicts a hold.
  virtual TargetSolve solve_targets(const std::vector<std::string>& targets,
                                    const Eigen::VectorXd& start,
                                    const std::vector<std::string>& held = {}) const = 0;
  // ImGui: the measurements panel, one row per measurement: the current best, the start and
  // the hovered cell (each may be null), a hold toggle (`holds`: those in force, as given to
  // hold_projector) and a target field with "Go".
  virtual MeasurementPanelRequest draw_measurement_panel(const PreparedCell* best,
                                                         const PreparedCell* start,
                                                         const PreparedCell* hovered,
                                                         const std::vector<std::string>& holds,
                                                         MeasurementPanelState& state) const = 0;
};

class DesignSpace {
 public:
  virtual ~DesignSpace() = default;

  // --- What it is ---
  virtual SpaceSettings settings() const = 0;
  // One line for the window: "body: default model, 10 components".
  virtual std::string description() const = 0;
  // What the search is on, in a few words, for the toolbar: "female (built-in)", "me.npz".
  virtual std::string source_label() const {
    const std::string source = settings().source;
    return source.empty() ? std::string("built-in")
                          : std::filesystem::path(source).filename().string();
  }
  int dimensions() const { return settings().dimensions; }
  // A short label for dimension i (the expert sliders): what moving it changes, in words a
  // designer reads ("taller, heavier").
  virtual std::string dimension_name(int i) const = 0;
  // More about it for a tooltip (its measured effect in numbers, its share of the variance).
  virtual std::string dimension_details(int /*i*/) const { return {}; }

  // --- Cells: CPU, GPU, ImGui ---
  // Bodies are 3D (one shared orbit camera); photos are flat.
  virtual bool uses_camera() const = 0;
  // Width / height of a preview (a standing body is taller than wide; a photo has its own).
  virtual float preview_aspect() const = 0;
  // CPU work for one cell; thread-safe. `details` adds what the inspector shows.
  virtual std::shared_ptr<const PreparedCell> prepare(const Eigen::VectorXd& x,
                                                      bool details) const = 0;
  // GL thread only. Contents may share GPU resources the space keeps (a photo's texture).
  virtual std::unique_ptr<CellContent> make_content() = 0;
  // ImGui: what `shown` is (measurements, parameters), beside `reference` and the difference
  // to it when given. Called inside an ImGui window, GL thread only.
  virtual void draw_inspector(const PreparedCell& shown, const char* shown_label,
                              const PreparedCell* reference, const char* reference_label) const = 0;
  // Named numbers of a prepared cell with details, for tables and CSV files (a body's
  // measurements in metres; nothing for a photo, whose x is all there is).
  virtual std::vector<std::pair<std::string, double>> numbers(const PreparedCell& /*cell*/) const {
    return {};
  }
  // One short line on how `cell` differs from `reference` (a body: its two most visible
  // measurement changes, "taller 8.2 cm, heavier 9.6 kg"), drawn inside a hovered cell so
  // that nothing covers the neighbours being compared. Empty: nothing to say.
  virtual std::string cell_summary(const PreparedCell& /*cell*/,
                                   const PreparedCell& /*reference*/) const {
    return {};
  }

  // --- Export: the file a point becomes (glTF for bodies, an image and its parameters) ---
  virtual std::string default_export_name() const = 0;  // "body.glb"
  virtual std::string export_hint() const = 0;          // ".glb or .gltf"
  // Writes the file(s) atomically; returns a short summary for the message line. Throws
  // std::runtime_error naming the file and the problem.
  virtual std::string export_point(const Eigen::VectorXd& x,
                                   const std::filesystem::path& path) const = 0;

  // --- Framing: a space whose cells show a camera may frame a grid on the part of the cells
  // where they differ (close-ups) or show them whole; the perception's distance follows.
  // Returns whether the space frames that way now (false: it has no close-ups). ---
  virtual bool set_close_ups(bool /*on*/) { return false; }
  virtual bool close_ups() const { return false; }

  // --- Optional facets: null where the space has none ---
  virtual const SpacePerception* perception() const { return nullptr; }
  virtual const SpaceMeasurements* measurements() const { return nullptr; }
};

// The space's measurements, or std::invalid_argument "this design space has no measurements
// to <what>" (a hold or a target asked of a photo).
inline const SpaceMeasurements& measurements_to(const DesignSpace& space, const char* what) {
  const SpaceMeasurements* m = space.measurements();
  if (m == nullptr)
    throw std::invalid_argument(std::string("this design space has no measurements to ") + what);
  return *m;
}

}  // namespace app
