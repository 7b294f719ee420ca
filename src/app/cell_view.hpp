// One drawn cell of the gallery (a grid cell, a preview, a history thumbnail), whatever the
// design space: the prepared point, its GPU content and its offscreen framebuffer. A cell is
// prepared again only when its point changes, and redrawn only when its content, the camera or
// its size changed. GL thread only.
#pragma once

#include <array>
#include <memory>

#include <Eigen/Core>

#include "app/design_space.hpp"
#include "render/cell_framebuffer.hpp"

namespace app {

struct CellView {
  std::unique_ptr<CellContent> content;
  std::shared_ptr<const PreparedCell> prepared;
  render::CellFramebuffer fbo;
  bool clamped = false;
  // The cell shows the current best (what Save writes now): labelled, so that a person sees
  // which cell keeps what they have, also where a plane near the box's faces shows it at an
  // edge or a corner.
  bool current = false;
  bool dirty = true;
  int drawn_camera = -1;
  int region_w = 0;
  int region_h = 0;
  bool drawn_fast = false;

  // Prepares and uploads `x` if it differs from what the cell shows (or `details` are wanted
  // and missing). Returns true if it did.
  bool set_point(DesignSpace& space, const Eigen::VectorXd& x, bool details);

  // Renders into the framebuffer if needed. `fast` (while animating) draws a `scale`d region
  // without multisampling unless `fast_multisample`; the settled image is drawn again at full
  // quality. Returns true if it drew.
  bool draw(const CellLook& look, int camera_version, int width, int height, int samples,
            bool fast = false, float scale = 1.0f, bool fast_multisample = false);

  // Texture coordinates {u0, v0, u1, v1} of the last drawn region, top-left to bottom-right.
  std::array<float, 4> uv() const;
};

}  // namespace app
