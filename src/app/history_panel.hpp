// The History tab: the choice of every finished plane as a thumbnail; clicking one inspects it.
// Thumbnails are kept as pictures only, each drawn once, from the front: neither orbiting the
// grid nor a long session makes them cost more.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "app/cell_view.hpp"
#include "app/panel_context.hpp"
#include "render/camera.hpp"

namespace app {

class HistoryPanel {
 public:
  HistoryPanel();
  // Before the frame: thumbnails of choices that changed are marked to be drawn again.
  void update(const Session& session);
  // GL: draws at most `budget` missing thumbnails of `width` x `height` pixels.
  void draw_thumbnails(DesignSpace& space, int width, int height, int samples, int budget);
  void draw(PanelContext& ctx);
  long draws() const { return draws_; }
  void release_gl() { thumbnails_.clear(); }

 private:
  struct Thumbnail {
    Eigen::VectorXd x;
    render::CellFramebuffer fbo;
    bool drawn = false;
  };
  std::vector<Thumbnail> thumbnails_;
  render::Camera camera_;
  long draws_ = 0;
};

}  // namespace app
