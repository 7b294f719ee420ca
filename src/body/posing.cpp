#include "body/posing.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "body/mesh_normals.hpp"

namespace body {

namespace {

int find_joint(const Model& model, const std::string& name) {
  const auto it = std::find(model.joint_names.begin(), model.joint_names.end(), name);
  return it == model.joint_names.end() ? -1 : static_cast<int>(it - model.joint_names.begin());
}

}  // namespace

Eigen::Matrix3f rotation_between(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return Eigen::Quaternionf::FromTwoVectors(a, b).normalized().toRotationMatrix();
}

Skinning::Skinning(const Model& model, const Rotations& local) : model_(model) {
  const int J = model.joint_count();
  if (static_cast<int>(local.size()) != J || static_cast<int>(model.parents.size()) != J) {
    throw ModelError(model.name + ": posing needs one rotation per joint (" + std::to_string(J) +
                     "), got " + std::to_string(local.size()));
  }
  // Parents before children: repeated passes over the (validated, acyclic) hierarchy.
  std::vector<char> placed(static_cast<std::size_t>(J), 0);
  while (static_cast<int>(order_.size()) < J) {
    for (int j = 0; j < J; ++j) {
      const int p = model.parents[static_cast<std::size_t>(j)];
      if (!placed[static_cast<std::size_t>(j)] && (p < 0 || placed[static_cast<std::size_t>(p)])) {
        placed[static_cast<std::size_t>(j)] = 1;
        order_.push_back(j);
      }
    }
  }
  global_.assign(static_cast<std::size_t>(J), Eigen::Matrix3f::Identity());
  for (int j : order_) {
    const int p = model.parents[static_cast<std::size_t>(j)];
    global_[static_cast<std::size_t>(j)] =
        p < 0 ? local[static_cast<std::size_t>(j)]
              : Eigen::Matrix3f(global_[static_cast<std::size_t>(p)] *
                                local[static_cast<std::size_t>(j)]);
  }
  Eigen::Matrix<float, Eigen::Dynamic, 9, Eigen::RowMajor> flat(J, 9);
  for (int j = 0; j < J; ++j) {
    const Eigen::Matrix<float, 3, 3, Eigen::RowMajor> r = global_[static_cast<std::size_t>(j)];
    flat.row(j) = Eigen::Map<const Eigen::Matrix<float, 1, 9>>(r.data());
  }
  blended_ = model.weights * flat;
}

Eigen::MatrixXf Skinning::translations(const Vertices& joints) const {
  // World transform of joint j: G_j = G_parent [R_j | J_j - J_parent]; the skinning transform
  // is G_j [I | -J_j], whose translation is G_j.t - R^global_j J_j.
  const int J = model_.joint_count();
  Vertices g(J, 3);
  for (int j : order_) {
    const int p = model_.parents[static_cast<std::size_t>(j)];
    if (p < 0) {
      g.row(j) = joints.row(j);
    } else {
      g.row(j) = g.row(p) + (global_[static_cast<std::size_t>(p)] *
                             (joints.row(j) - joints.row(p)).transpose())
                                .transpose();
    }
  }
  Eigen::MatrixXf t(J, 3);
  for (int j = 0; j < J; ++j) {
    t.row(j) =
        g.row(j) - (global_[static_cast<std::size_t>(j)] * joints.row(j).transpose()).transpose();
  }
  return t;
}

Vertices Skinning::vertices(const Vertices& v, const Vertices& joints) const {
  const Eigen::MatrixXf t = translations(joints);
  Vertices out = model_.weights * t;  // V x 3
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Map<const Eigen::Matrix<float, 3, 3, Eigen::RowMajor>> r(blended_.row(i).data());
    out.row(i) += (r * v.row(i).transpose()).transpose();
  }
  return out;
}

Vertices Skinning::joints(const Vertices& joints) const {
  const Eigen::MatrixXf t = translations(joints);
  Vertices out(joints.rows(), 3);
  for (Eigen::Index j = 0; j < joints.rows(); ++j) {
    out.row(j) =
        t.row(j) + (global_[static_cast<std::size_t>(j)] * joints.row(j).transpose()).transpose();
  }
  return out;
}

Eigen::VectorXf pose_correctives(const Model& model, const Rotations& local) {
  const Eigen::Index J = model.joint_count();
  if (model.posedirs.size() == 0 || model.posedirs.cols() != 9 * (J - 1) ||
      model.posedirs.rows() != 3 * model.vertex_count()) {
    return {};
  }
  Eigen::VectorXf feature(9 * (J - 1));
  for (Eigen::Index j = 1; j < J; ++j) {
    const Eigen::Matrix<float, 3, 3, Eigen::RowMajor> d =
        local[static_cast<std::size_t>(j)] - Eigen::Matrix3f::Identity();
    feature.segment(9 * (j - 1), 9) = Eigen::Map<const Eigen::VectorXf>(d.data(), 9);
  }
  return model.posedirs * feature;
}

Rotations t_pose_rotations(const Model& model, const Vertices& rest_joints) {
  Rotations local(static_cast<std::size_t>(model.joint_count()), Eigen::Matrix3f::Identity());
  for (const std::string side : {"left", "right"}) {
    const int sh = find_joint(model, side + "_shoulder");
    const int el = find_joint(model, side + "_elbow");
    const int wr = find_joint(model, side + "_wrist");
    if (sh < 0 || el < 0 || wr < 0) {
      throw ModelError(model.name +
                       ": a T-pose needs the SMPL-family arm joints (left_/right_ shoulder, "
                       "elbow, wrist); this skeleton has " +
                       std::to_string(model.joint_count()) + " joints without them");
    }
    // Global rotations of the shoulder's ancestors are identity in the rest pose.
    const Eigen::Vector3f s = rest_joints.row(sh).transpose();
    const Eigen::Vector3f e = rest_joints.row(el).transpose();
    const Eigen::Vector3f w = rest_joints.row(wr).transpose();
    const Eigen::Vector3f upper = e - s, fore = w - e;
    if (!(upper.norm() > 1e-6f) || !(fore.norm() > 1e-6f)) {
      throw ModelError(model.name + ": the " + side + " arm's joints coincide; no T-pose");
    }
    // Outward along x: the side the elbow already lies on (SMPL's left is +x).
    const Eigen::Vector3f out(upper.x() >= 0.0f ? 1.0f : -1.0f, 0.0f, 0.0f);
    const Eigen::Matrix3f r_sh = rotation_between(upper.normalized(), out);
    const Eigen::Vector3f fore_after = r_sh * fore.normalized();
    const Eigen::Matrix3f r_el_global = rotation_between(fore_after, out) * r_sh;
    local[static_cast<std::size_t>(sh)] = r_sh;
    local[static_cast<std::size_t>(el)] = r_sh.transpose() * r_el_global;
  }
  return local;
}

BodyMesh t_posed(const Model& model, const BodyMesh& shaped, bool* correctives_applied) {
  const Rotations local = t_pose_rotations(model, shaped.joints);
  const Skinning skin(model, local);
  Vertices v = shaped.vertices;
  const Eigen::VectorXf offsets = pose_correctives(model, local);
  const bool use = offsets.size() == 3 * v.rows();
  if (use) Eigen::Map<Eigen::VectorXf>(v.data(), offsets.size()) += offsets;
  if (correctives_applied) *correctives_applied = use;
  BodyMesh out;
  out.vertices = skin.vertices(v, shaped.joints);
  out.joints = skin.joints(shaped.joints);
  place_on_ground(out);
  compute_vertex_normals(out.vertices, model.faces, out.normals);
  return out;
}

}  // namespace body
