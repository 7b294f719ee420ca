// A texture layout (UVs) for the template mesh, stored as SMPL-X stores its own: `vt` (T x 2,
// origin bottom left) and `ft` (F x 3, indices into vt). Charts follow the body's parts, with
// seams where artists put them: round the neck, shoulders, wrists, hips and ankles; along the
// inner arms and legs; down the sides of the torso; behind the head (a vertical plane behind
// the ears) and round the face (in front of the cheekbones); between the back and palm of each hand
// and between sole and top of each foot. Each chart is flattened by least squares conformal maps
// (Levy, Petitjean, Ray & Maillot 2002), scaled to its surface area (one texel density everywhere)
// and packed into [0, 1]^2.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "implicit_mesher.hpp"
#include "smplx_rig.hpp"

namespace default_model {

struct UvLayout {
  std::vector<Eigen::Vector2d> uv;        // T entries in [0, 1]^2
  std::vector<std::array<int, 3>> faces;  // F entries, the mesh's faces' corners into uv
  std::vector<int> chart_of_face;         // F entries
  int charts = 0;
};

struct UvDistortion {
  int charts = 0, non_disk_charts = 0;
  int flipped_faces = 0;
  double area_log2_mean = 0, area_log2_p95 = 0;  // |log2 of (UV area share / 3-D area share)|
  double angle_mean_deg = 0, angle_p95_deg = 0;  // |UV corner angle - 3-D corner angle|
  double packing = 0;                            // share of [0, 1]^2 the charts cover
  std::string describe() const;
};

// `weights` is the rig's V x J skin weights (heat_weights): a face's body part is that of the
// joint with the largest summed weight over its corners.
UvLayout uv_layout(const TriMesh& mesh, const SmplxRig& rig, const Eigen::MatrixXd& weights);

UvDistortion uv_distortion(const TriMesh& mesh, const UvLayout& layout);

}  // namespace default_model
