// Tape-measure girths from horizontal slices.
//
// Landmark choice. SMPL-family meshes carry no landmark labels that are shared across models,
// so the landmarks are relative heights of the standing body. Classic anthropometric
// proportions (Drillis & Contini 1966, as tabulated in Winter, "Biomechanics and Motor Control
// of Human Movement": shoulder 0.818 H, chest/nipple ~0.72 H, navel/waist ~0.60 H, greater
// trochanter/hip ~0.53 H, crotch ~0.47 H) put each landmark inside a band; within the band the
// tailoring definitions pick the slice (chest = maximum girth, waist = minimum girth of the
// torso, hip = maximum girth below the waist). Bands stop below the armpit (0.75 H) so
// T-posed arms stay out, and the hip band starts at 0.45 H where the legs split. Arms that
// hang beside the body are separate slice pieces and are dropped; where they merge with the
// torso at the armpit (short bodies in A-pose reach that below 0.75 H) the girth jumps by
// more than 15% between neighbouring slices and the chest search stops there.
#include "body/measurements.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "body/convex_hull.hpp"
#include "body/mesh_slice.hpp"

namespace body {

double torso_girth(const BodyMesh& mesh, const Faces& faces, double y, double axis_x,
                   double axis_z) {
  const Eigen::Vector2d axis(axis_x, axis_z);
  double best = 0.0;
  for (const auto& piece : slice_mesh(mesh.vertices, faces, y)) {
    const auto hull = convex_hull(piece.points);
    if (!hull_contains(hull, axis)) continue;
    best = std::max(best, polygon_perimeter(hull));
  }
  return best;
}

double enclosed_volume(const Vertices& vertices, const Faces& faces) {
  double six_volume = 0.0;
  const Eigen::Index V = vertices.rows();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (faces(f, 0) >= V || faces(f, 1) >= V || faces(f, 2) >= V) continue;
    const Eigen::Vector3d a = vertices.row(faces(f, 0)).cast<double>().transpose();
    const Eigen::Vector3d b = vertices.row(faces(f, 1)).cast<double>().transpose();
    const Eigen::Vector3d c = vertices.row(faces(f, 2)).cast<double>().transpose();
    six_volume += a.dot(b.cross(c));
  }
  return std::abs(six_volume) / 6.0;
}

Measurements measure(const Model& model, const BodyMesh& mesh) {
  Measurements m;
  const Eigen::Index V = mesh.vertices.rows();
  if (V == 0) return m;
  m.volume = enclosed_volume(mesh.vertices, model.faces);
  m.mass = kBodyDensity * m.volume;
  const double ymin = mesh.vertices.col(1).minCoeff();
  const double ymax = mesh.vertices.col(1).maxCoeff();
  const double H = ymax - ymin;
  m.height = H;
  if (!(H > 0.0)) return m;
  const double ax = mesh.vertices.col(0).cast<double>().mean();
  const double az = mesh.vertices.col(2).cast<double>().mean();
  const int steps = 200;
  auto girth_at = [&](int i) {
    return torso_girth(mesh, model.faces, ymin + H * i / steps, ax, az);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  m.chest_height = m.waist_height = m.hips_height = nan;

  double previous = 0.0;
  for (int i = 130; i <= 150; ++i) {  // chest: max in [0.65, 0.75] H, below the armpits
    const double g = girth_at(i);
    // Arms that hang close (A-pose) join the torso slice at the armpit: the girth jumps from
    // one slice to the next (0.5% of H apart) by far more than a chest ever grows. Stop there.
    if (previous > 0.0 && g > 1.15 * previous) break;
    previous = g;
    if (g > m.chest) m.chest = g, m.chest_height = H * i / steps;
  }
  int waist_i = -1;
  double waist = std::numeric_limits<double>::infinity();
  for (int i = 112; i <= 134; ++i) {  // waist: min in [0.56, 0.67] H
    const double g = girth_at(i);
    if (g > 0.0 && g < waist) waist = g, waist_i = i;
  }
  if (waist_i >= 0) m.waist = waist, m.waist_height = H * waist_i / steps;
  const int hip_top = waist_i >= 0 ? waist_i : 120;
  for (int i = 90; i <= hip_top; ++i) {  // hips: max from 0.45 H up to the waist
    const double g = girth_at(i);
    if (g > m.hips) m.hips = g, m.hips_height = H * i / steps;
  }
  return m;
}

Measurements measure(const Model& model, const Eigen::VectorXf& betas) {
  return measure(model, evaluate(model, betas));
}

}  // namespace body
