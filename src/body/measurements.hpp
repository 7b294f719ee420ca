// Measurements a body designer reads: stature and tape-measure girths.
#pragma once

#include "body/body_model.hpp"

namespace body {

struct Measurements {
  double height = 0.0;  // metres, top of head to sole
  double chest = 0.0;   // circumferences in metres (convex hull of a horizontal slice)
  double waist = 0.0;
  double hips = 0.0;
  // Heights above the sole (metres) of the slices the girths were taken at; NaN if the
  // band held no torso slice (then the girth is 0).
  double chest_height = 0.0;
  double waist_height = 0.0;
  double hips_height = 0.0;
};

// Landmarks (see measurements.cpp for the sources): with H the stature and the body standing
// in y, slices every H/200 through three bands of relative height,
//   chest = largest torso girth in [0.65, 0.75] H   (bust line, below the armpits; the
//           search stops where the girth jumps by > 15% between slices: arms joining),
//   waist = smallest torso girth in [0.56, 0.67] H  (natural waist),
//   hips  = largest torso girth from 0.45 H up to the waist slice (seat / buttocks).
// A girth is the perimeter of the convex hull of the slice piece that surrounds the body's
// vertical axis (mean x and z of all vertices), so arms and hands beside the torso and the two
// legs below the crotch are left out, as a tape measure would leave them out.
Measurements measure(const Model& model, const BodyMesh& mesh);

// Convenience: evaluate(model, betas) then measure.
Measurements measure(const Model& model, const Eigen::VectorXf& betas);

// Girth of the torso piece at height y (absolute, in the mesh's frame); 0 if no slice piece
// surrounds the vertical axis at (axis_x, axis_z).
double torso_girth(const BodyMesh& mesh, const Faces& faces, double y, double axis_x,
                   double axis_z);

}  // namespace body
