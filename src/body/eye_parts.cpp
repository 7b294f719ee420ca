#include "body/eye_parts.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace body {

std::vector<EyePart> eye_parts(const Model& model) {
  const Eigen::Index V = model.v_template.rows();
  std::vector<EyePart> parts(static_cast<std::size_t>(V), EyePart::kSkin);
  if (model.weights.rows() != V || model.j_regressor.cols() != V) return parts;
  const float iris_cosine = std::cos(0.52f);  // 30 degrees
  for (const char* name : {"left_eye_smplhf", "right_eye_smplhf"}) {
    const auto it = std::find(model.joint_names.begin(), model.joint_names.end(), name);
    if (it == model.joint_names.end()) continue;
    const auto e = static_cast<Eigen::Index>(it - model.joint_names.begin());
    if (e >= model.weights.cols() || e >= model.j_regressor.rows()) continue;
    const Eigen::RowVector3f centre = model.j_regressor.row(e) * model.v_template;
    for (Eigen::Index v = 0; v < V; ++v) {
      if (model.weights(v, e) < 0.99f) continue;
      const Eigen::RowVector3f d = model.v_template.row(v) - centre;
      const float length = d.norm();
      parts[static_cast<std::size_t>(v)] =
          length > 0.0f && d.z() > iris_cosine * length ? EyePart::kIris : EyePart::kWhite;
    }
  }
  return parts;
}

}  // namespace body
