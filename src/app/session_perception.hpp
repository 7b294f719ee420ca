// What a design space's perception (how a person sees its points) gives a search: one place
// for the window's controller and for `render-grid`, so that a grid rendered from the command
// line is the grid the window would show with cells of the same size.
#pragma once

#include <Eigen/Core>

#include "app/design_space.hpp"
#include "app/session.hpp"

namespace app {

// The space's full perceptual metric where it has one that fits `scale` (its diagonal the
// scale squared, to 0.1%: a session saved on another model keeps its own scale alone); else
// empty, the scale alone.
Eigen::MatrixXd usable_metric(const SpacePerception& perception, const Eigen::VectorXd& scale);

// Gives `session` what `perception` says, for cells `cell_px` pixels high (0: not known yet).
// A new session (no perceptual scale yet) takes the space's scale and metric, plane length,
// choice noise, uncertainty-plane size and plane axes. A session restored from a file keeps
// what it was saved with (its planes were built with it) and gains only what it was saved
// without: the full metric and the population. With `perceptual_zoom` the zoom adapts to
// what the cells show (else the paper's fixed zoom).
void install_perception(Session& session, const SpacePerception& perception, int cell_px,
                        bool perceptual_zoom);

// The cells are now `cell_px` pixels high: the zoom policy at once (the grid on screen stays),
// the plane length and choice noise from the next plane on.
void follow_cell_size(Session& session, const SpacePerception& perception, int cell_px);

}  // namespace app
