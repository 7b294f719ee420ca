// The Measurements tab: the shown body's, the start's and the hovered cell's measurements,
// the holds and typed targets (the space draws the table; the panel keeps what was typed and
// queues what was asked). Spaces without measurements show their inspector instead.
#pragma once

#include "app/panel_context.hpp"

namespace app {

class MeasurementsPanel {
 public:
  void draw(PanelContext& ctx, const PreparedCell* shown, const PreparedCell* start,
            const PreparedCell* hovered, bool inspecting);

 private:
  MeasurementPanelState state_;
};

}  // namespace app
