#include "app/cell_view.hpp"

#include <algorithm>
#include <cmath>

namespace app {

bool CellView::set_point(DesignSpace& space, const Eigen::VectorXd& x, bool details) {
  const bool same =
      prepared && prepared->x.size() == x.size() && (prepared->x - x).cwiseAbs().maxCoeff() < 1e-12;
  if (same && (!details || prepared->has_details)) return false;
  prepared = space.prepare(x, details);
  if (!content) content = space.make_content();
  if (!same) {
    content->upload(*prepared);
    dirty = true;
  }
  return true;
}

bool CellView::draw(const CellLook& look, int camera_version, int width, int height, int samples,
                    bool fast, float scale, bool fast_multisample) {
  if (!content) return false;
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
  content->draw(region_w, region_h, look);
  fbo.end(region_w, region_h, multisample);
  dirty = false;
  drawn_fast = fast;
  drawn_camera = camera_version;
  return true;
}

std::array<float, 4> CellView::uv() const {
  float a[2], b[2];
  fbo.region_uv(region_w, region_h, a, b);
  return {a[0], a[1], b[0], b[1]};
}

}  // namespace app
