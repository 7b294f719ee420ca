// Measurements a body designer reads: stature and tape-measure girths.
#pragma once

#include "body/body_model.hpp"

namespace body {

struct Measurements {
  double height = 0.0;  // metres, top of head to sole
  double chest = 0.0;   // circumferences in metres (convex hull of a horizontal slice)
  double waist = 0.0;
  double hips = 0.0;
};

Measurements measure(const Model& model, const BodyMesh& mesh);

}  // namespace body
