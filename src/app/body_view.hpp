// One rendered body of the viewer (a grid cell, a preview or a history thumbnail): its GPU
// mesh, its offscreen framebuffer, and what it last showed, so it is re-evaluated only when its
// point changes and redrawn only when the body, the camera or the size changed.
#pragma once

#include <array>
#include <optional>

#include <Eigen/Core>

#include "body/body_model.hpp"
#include "body/measurements.hpp"
#include "render/body_renderer.hpp"
#include "render/camera.hpp"
#include "render/cell_framebuffer.hpp"
#include "render/mesh_gpu.hpp"

namespace app {

struct BodyView {
  render::MeshGpu mesh;
  render::CellFramebuffer fbo;
  Eigen::VectorXd x;
  bool clamped = false;
  bool dirty = true;
  int drawn_camera = -1;
  int region_w = 0;
  int region_h = 0;
  bool drawn_fast = false;
  std::optional<body::Measurements> measurements;

  // Re-evaluates the body if `point` differs from x. Returns true if it did.
  bool set_body(const body::Model& model, const Eigen::VectorXd& point, bool want_measurements);

  // Renders into the framebuffer if the body, the camera or the size changed. `fast` (while
  // animating) draws a `scale`d region without multisampling unless `fast_multisample`; the
  // settled image is drawn again at full quality. Returns true if it drew.
  bool draw(render::BodyRenderer& renderer, const render::Camera& camera, int camera_version,
            int width, int height, int samples, const render::BodyStyle& style, bool fast = false,
            float scale = 1.0f, bool fast_multisample = false);

  // Texture coordinates {u0, v0, u1, v1} of the last drawn region, top-left to bottom-right.
  std::array<float, 4> uv() const;
};

}  // namespace app
