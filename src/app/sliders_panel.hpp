// The Sliders tab, the paper's user-study request: direct control for experts. The sliders
// start at the current best; the preview follows them; "Use this" submits the point as
// preferred over the previous best (it becomes the current best).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "app/panel_context.hpp"

namespace app {

class SlidersPanel {
 public:
  void draw(PanelContext& ctx);
  // While set, the "current best" preview shows this point instead.
  const std::optional<Eigen::VectorXd>& point() const { return x_; }
  // A space of another size opened: the sliders' point means nothing there.
  void space_opened() { x_.reset(); }

 private:
  std::optional<Eigen::VectorXd> x_;
};

}  // namespace app
