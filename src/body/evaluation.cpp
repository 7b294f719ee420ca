// betas -> vertices, joints and normals; the unit-box mapping of the paper.
#include <cmath>
#include <stdexcept>
#include <string>

#include "body/body_model.hpp"
#include "body/mesh_normals.hpp"

namespace body {

void Model::prepare() {
  if (j_regressor.cols() != v_template.rows() || shapedirs.rows() != 3 * v_template.rows()) {
    joint_template.resize(0, 3);
    joint_shapedirs.resize(0, 0);
    return;
  }
  const Eigen::Index J = j_regressor.rows();
  const Eigen::Index K = shapedirs.cols();
  joint_template = j_regressor * v_template;
  joint_shapedirs.resize(3 * J, K);
  // shapedirs is column-major 3V x K: column k viewed as V x 3 row-major is that component's
  // displacement field, so each column maps with one J x V by V x 3 product.
  for (Eigen::Index k = 0; k < K; ++k) {
    Eigen::Map<const Vertices> field(shapedirs.col(k).data(), v_template.rows(), 3);
    Vertices jk = j_regressor * field;
    Eigen::Map<Eigen::VectorXf>(joint_shapedirs.col(k).data(), 3 * J) =
        Eigen::Map<const Eigen::VectorXf>(jk.data(), 3 * J);
  }
}

BodyMesh evaluate(const Model& model, const Eigen::VectorXf& betas) {
  const Eigen::Index K = model.shapedirs.cols();
  const Eigen::Index V = model.v_template.rows();
  if (betas.size() > K) {
    throw std::invalid_argument("evaluate: " + std::to_string(betas.size()) +
                                " betas given but the model '" + model.name + "' keeps " +
                                std::to_string(K) + " shape components");
  }
  for (Eigen::Index i = 0; i < betas.size(); ++i) {
    if (!std::isfinite(betas[i])) {
      throw std::invalid_argument("evaluate: beta " + std::to_string(i) + " is not finite");
    }
  }
  const Eigen::Index n = betas.size();
  BodyMesh mesh;
  mesh.vertices = model.v_template;
  Eigen::Map<Eigen::VectorXf> flat(mesh.vertices.data(), 3 * V);
  if (n > 0) flat.noalias() += model.shapedirs.leftCols(n) * betas;

  const Eigen::Index J = model.j_regressor.rows();
  if (model.joint_template.rows() == J && model.joint_shapedirs.rows() == 3 * J &&
      model.joint_shapedirs.cols() == K) {
    mesh.joints = model.joint_template;
    Eigen::Map<Eigen::VectorXf> jflat(mesh.joints.data(), 3 * J);
    if (n > 0) jflat.noalias() += model.joint_shapedirs.leftCols(n) * betas;
  } else {
    mesh.joints = model.j_regressor * mesh.vertices;
  }
  compute_vertex_normals(mesh.vertices, model.faces, mesh.normals);
  return mesh;
}

float place_on_ground(BodyMesh& mesh) {
  if (mesh.vertices.rows() == 0) return 0.0f;
  const float offset = -mesh.vertices.col(1).minCoeff();
  mesh.vertices.col(1).array() += offset;
  if (mesh.joints.rows() > 0) mesh.joints.col(1).array() += offset;
  return offset;
}

Eigen::VectorXf betas_from_unit(const Eigen::VectorXd& x) {
  return (6.0 * x.array() - 3.0).cast<float>().matrix();
}

Eigen::VectorXd unit_from_betas(const Eigen::VectorXf& betas) {
  return ((betas.cast<double>().array() + 3.0) / 6.0).matrix();
}

}  // namespace body
