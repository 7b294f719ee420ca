// Measurements a body designer reads: stature, tape-measure girths, body volume and mass.
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
  // Enclosed volume (m^3, signed tetrahedra; its absolute value, so either winding works) and
  // the body mass it implies at kBodyDensity (kg). Meaningful for closed meshes (the built-in
  // models, SMPL); open meshes (holes at the neck of a head-less model...) read low.
  double volume = 0.0;
  double mass = 0.0;
};

// Whole-body density, kg/m^3. Densitometry of adults gives about 1.06-1.07 g/cm^3 for lean
// tissue and 0.90 for fat; whole-body densities with the lungs' air included are close to
// water: 985 kg/m^3 is the value of the project's domain notes (Anny uses 980). Brozek et al.
// 1963 (Ann. N. Y. Acad. Sci. 110:113) and Siri 1961 give the tissue densities.
constexpr double kBodyDensity = 985.0;

// Volume enclosed by a closed triangle mesh (m^3): |sum over triangles of det(a, b, c) / 6|.
double enclosed_volume(const Vertices& vertices, const Faces& faces);

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
