// betas -> vertices, joints and normals; the unit-box mapping of the paper.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/QR>
#include <Eigen/SparseCore>

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
  // SMPL-family regressors are sparse (a few dozen vertices per joint): a sparse copy makes
  // this J x V by V x 3K product cheap even for 400 components.
  const Eigen::SparseMatrix<float, Eigen::RowMajor> regressor = j_regressor.sparseView();
  joint_template = regressor * v_template;
  joint_shapedirs.resize(3 * J, K);
  // shapedirs is column-major 3V x K: column k viewed as V x 3 row-major is that component's
  // displacement field, so each column maps with one J x V by V x 3 product.
  for (Eigen::Index k = 0; k < K; ++k) {
    Eigen::Map<const Vertices> field(shapedirs.col(k).data(), v_template.rows(), 3);
    const Vertices jk = regressor * field;
    Eigen::Map<Eigen::VectorXf>(joint_shapedirs.col(k).data(), 3 * J) =
        Eigen::Map<const Eigen::VectorXf>(jk.data(), 3 * J);
  }
}

namespace {

void check_betas(const Model& model, const Eigen::VectorXf& betas) {
  const Eigen::Index K = model.shapedirs.cols();
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
}

}  // namespace

namespace {

// out = S.leftCols(M.rows()) * M for a tall S (3V x K, column-major) and a narrow M (K x c):
// column by column rank-1 updates, so S streams from memory once and the 3V x c result stays
// in cache. A general GEMM packs (copies) S first, which costs more than the product here.
Eigen::MatrixXf tall_times_narrow(const Eigen::MatrixXf& S, const Eigen::MatrixXf& M) {
  Eigen::MatrixXf out = Eigen::MatrixXf::Zero(S.rows(), M.cols());
  for (Eigen::Index k = 0; k < M.rows(); ++k) {
    const auto col = S.col(k);
    for (Eigen::Index j = 0; j < M.cols(); ++j) out.col(j) += M(k, j) * col;
  }
  return out;
}

bool has_joint_cache(const Model& model) {
  const Eigen::Index J = model.j_regressor.rows();
  return model.joint_template.rows() == J && model.joint_shapedirs.rows() == 3 * J &&
         model.joint_shapedirs.cols() == model.shapedirs.cols();
}

void shape_into(const Model& model, const Eigen::VectorXf& betas, BodyMesh& mesh) {
  check_betas(model, betas);
  const Eigen::Index V = model.v_template.rows();
  const Eigen::Index J = model.j_regressor.rows();
  const Eigen::Index n = betas.size();
  mesh.vertices = model.v_template;  // reuses the storage when the size matches
  Eigen::Map<Eigen::VectorXf> flat(mesh.vertices.data(), 3 * V);
  if (n > 0) flat.noalias() += model.shapedirs.leftCols(n) * betas;
  if (has_joint_cache(model)) {
    mesh.joints = model.joint_template;
    Eigen::Map<Eigen::VectorXf> jflat(mesh.joints.data(), 3 * J);
    if (n > 0) jflat.noalias() += model.joint_shapedirs.leftCols(n) * betas;
  } else {
    mesh.joints.resize(J, 3);
    mesh.joints.noalias() = model.j_regressor * mesh.vertices;
  }
}

}  // namespace

void evaluate_into(const Model& model, const Eigen::VectorXf& betas, BodyMesh& mesh) {
  shape_into(model, betas, mesh);
  compute_vertex_normals(mesh.vertices, model.faces, mesh.normals);
}

BodyMesh evaluate_shape(const Model& model, const Eigen::VectorXf& betas) {
  BodyMesh mesh;
  shape_into(model, betas, mesh);
  return mesh;
}

BodyMesh evaluate(const Model& model, const Eigen::VectorXf& betas) {
  BodyMesh mesh;
  evaluate_into(model, betas, mesh);
  return mesh;
}

void evaluate_batch_into(const Model& model, const std::vector<Eigen::VectorXf>& betas,
                         std::vector<BodyMesh>& out) {
  const Eigen::Index V = model.v_template.rows();
  const Eigen::Index J = model.j_regressor.rows();
  const auto N = static_cast<Eigen::Index>(betas.size());
  Eigen::Index used = 0;  // components any body uses
  for (const auto& b : betas) {
    check_betas(model, b);
    used = std::max(used, b.size());
  }
  out.resize(betas.size());
  // With few components the per-body matrix-vector products are faster (no packing); with
  // many, one matrix-matrix product reads the 3V x K shapedirs once for all bodies.
  if (used <= 32) {
    for (std::size_t i = 0; i < betas.size(); ++i) evaluate_into(model, betas[i], out[i]);
    return;
  }
  Eigen::MatrixXf B = Eigen::MatrixXf::Zero(used, N);
  for (Eigen::Index i = 0; i < N; ++i) {
    B.col(i).head(betas[static_cast<std::size_t>(i)].size()) = betas[static_cast<std::size_t>(i)];
  }
  // The grid's nine bodies lie on a plane through shape space (c + s u + t v), so B has rank
  // 3, not 9. Factor B = Q R (column-pivoting QR in double) and form (shapedirs * Q) * R: the
  // expensive product then has r columns instead of N. Directions below 1e-6 of the largest
  // pivot are dropped (a change of < 1e-6 in betas, micrometres on the body).
  const bool fast_joints = has_joint_cache(model);
  Eigen::MatrixXf D, DJ;  // 3V x N and 3J x N shape displacements
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr =
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(B.cast<double>()).setThreshold(1e-6);
  const Eigen::Index r = qr.rank();
  if (r < N) {
    const Eigen::MatrixXf Q =
        (qr.householderQ() * Eigen::MatrixXd::Identity(used, r)).cast<float>();  // used x r
    const Eigen::MatrixXd Rr = qr.matrixR().topRows(r).triangularView<Eigen::Upper>();
    const Eigen::MatrixXf R = (Rr * qr.colsPermutation().transpose()).cast<float>();  // r x N
    const Eigen::MatrixXf SQ = tall_times_narrow(model.shapedirs, Q);                 // 3V x r
    D.noalias() = SQ * R;
    if (fast_joints) DJ.noalias() = (model.joint_shapedirs.leftCols(used) * Q) * R;
  } else {
    D = tall_times_narrow(model.shapedirs, B);
    if (fast_joints) DJ.noalias() = model.joint_shapedirs.leftCols(used) * B;
  }
  for (Eigen::Index i = 0; i < N; ++i) {
    BodyMesh& mesh = out[static_cast<std::size_t>(i)];
    mesh.vertices = model.v_template;
    Eigen::Map<Eigen::VectorXf>(mesh.vertices.data(), 3 * V) += D.col(i);
    if (fast_joints) {
      mesh.joints = model.joint_template;
      Eigen::Map<Eigen::VectorXf>(mesh.joints.data(), 3 * J) += DJ.col(i);
    } else {
      mesh.joints.resize(J, 3);
      mesh.joints.noalias() = model.j_regressor * mesh.vertices;
    }
    compute_vertex_normals(mesh.vertices, model.faces, mesh.normals);
  }
}

std::vector<BodyMesh> evaluate_batch(const Model& model,
                                     const std::vector<Eigen::VectorXf>& betas) {
  std::vector<BodyMesh> out;
  evaluate_batch_into(model, betas, out);
  return out;
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
