#include "app/body_view.hpp"

#include <algorithm>
#include <cmath>

#include "app/body_scene.hpp"

namespace app {

bool BodyView::set_body(const body::Model& model, const Eigen::VectorXd& point,
                        bool want_measurements) {
  if (x.size() == point.size() && (x - point).cwiseAbs().maxCoeff() < 1e-12 && !mesh.empty()) {
    if (want_measurements && !measurements) {
      measurements = body::measure(model, body_at(model, x));
    }
    return false;
  }
  x = point;
  const body::BodyMesh m = body_at(model, x);
  show_mesh(mesh, model, m);
  measurements.reset();
  if (want_measurements) measurements = body::measure(model, m);
  dirty = true;
  return true;
}

bool BodyView::draw(render::BodyRenderer& renderer, const render::Camera& camera,
                    int camera_version, int width, int height, int samples,
                    const render::BodyStyle& style, bool fast, float scale, bool fast_multisample) {
  width = std::max(width, 16);
  height = std::max(height, 16);
  if (fbo.width() != width || fbo.height() != height || fbo.samples() != samples ||
      fbo.texture() == 0) {
    fbo.resize(width, height, samples);
    dirty = true;
  }
  if (!dirty && drawn_camera == camera_version && !(drawn_fast && !fast)) return false;
  const float s = fast ? std::clamp(scale, 0.25f, 1.0f) : 1.0f;
  region_w = std::max(16, static_cast<int>(std::lround(static_cast<float>(width) * s)));
  region_h = std::max(16, static_cast<int>(std::lround(static_cast<float>(height) * s)));
  const bool multisample = !fast || fast_multisample;
  fbo.set_linear_filtering(region_w != width || region_h != height);
  fbo.begin(region_w, region_h, multisample);
  renderer.draw(mesh, camera, region_w, region_h, style);
  fbo.end(region_w, region_h, multisample);
  dirty = false;
  drawn_fast = fast;
  drawn_camera = camera_version;
  return true;
}

std::array<float, 4> BodyView::uv() const {
  float a[2], b[2];
  fbo.region_uv(region_w, region_h, a, b);
  return {a[0], a[1], b[0], b[1]};
}

}  // namespace app
