// A PCA body model of the SMPL family (SMPL, SMPL+H, SMPL-X, STAR, or the embedded default
// model) held as plain Eigen data, and its evaluation betas -> mesh. No GL here.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace body {

using Vertices = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;  // V x 3, metres, y up
using Faces = Eigen::Matrix<std::uint32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;  // F x 3

// Errors loading or validating a model; what() names the file, the array and the problem.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Model {
  std::string name;     // e.g. "SMPL (neutral)" or the file stem
  std::string source;   // file path the model came from, or "<embedded neutral>" (female, male)
  Vertices v_template;  // V x 3
  Eigen::MatrixXf shapedirs;    // 3V x K: row 3*v + axis, column = component (only the K kept)
  Faces faces;                  // F x 3, indices < V
  Eigen::MatrixXf j_regressor;  // J x V (dense)
  Eigen::MatrixXf weights;      // V x J skinning weights
  std::vector<int> parents;     // J entries, -1 for the root
  std::vector<std::string> joint_names;  // J entries (built-in SMPL-family names by joint count)
  int total_components = 0;        // shape components in the file before truncation (SMPL-X: not
                                   // counting its expression components)
  Eigen::VectorXf variance_share;  // optional: share of variance of each kept component

  // SMPL-X keeps facial expressions in the same `shapedirs` array after its shape components
  // (300 + 100 in v1.1, 10 + 10 in v1.0). They are split off here: never explored, exported
  // only when asked for. 3V x E, the first E kept of total_expressions.
  Eigen::MatrixXf expression_dirs;
  int total_expressions = 0;

  // Optional pose correctives (`posedirs`, 3V x P, row 3v + axis), read on demand by
  // load_pose_correctives(). In SMPL's layout P = 9 (J-1) and the feature is (R_j - I) row by
  // row for joints 1..J-1; other layouts (STAR's) are kept but not applied.
  Eigen::MatrixXf posedirs;

  // Optional texture coordinates (`vt`, T x 2, origin bottom left) and per-face indices into
  // them (`ft`, F x 3, one row per row of `faces`).
  Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor> uvs;
  Faces uv_faces;

  // Joints are linear in betas too: joints = joint_template + joint_shapedirs * betas, with
  // joint_template = J_regressor * v_template and joint_shapedirs = J_regressor * shapedirs
  // (3J x K, row 3*j + axis). Filled by the loader and by prepare(); evaluate() falls back to
  // J_regressor * vertices when their sizes do not match the arrays above.
  Vertices joint_template;
  Eigen::MatrixXf joint_shapedirs;

  // Recomputes joint_template and joint_shapedirs; call after editing the arrays by hand.
  void prepare();

  int vertex_count() const { return static_cast<int>(v_template.rows()); }
  int component_count() const { return static_cast<int>(shapedirs.cols()); }
  int joint_count() const { return static_cast<int>(j_regressor.rows()); }
};

struct BodyMesh {
  Vertices vertices;  // V x 3
  Vertices normals;   // V x 3, unit, area-weighted vertex normals
  Vertices joints;    // J x 3 (J_regressor * vertices)
};

// Shape coefficients; missing trailing entries are 0, extra entries are an error.
// Evaluates v_template + shapedirs * betas, joints, normals. Throws std::invalid_argument on
// too many or non-finite betas.
BodyMesh evaluate(const Model& model, const Eigen::VectorXf& betas);

// Evaluates several bodies at once (e.g. the nine of a 3x3 grid): one matrix-matrix product
// reads shapedirs once instead of once per body, which matters with hundreds of components.
// Same results and errors as evaluate().
std::vector<BodyMesh> evaluate_batch(const Model& model, const std::vector<Eigen::VectorXf>& betas);

// The same, writing into existing meshes so their storage is reused from frame to frame
// (no allocation or page faults when the sizes already match).
void evaluate_into(const Model& model, const Eigen::VectorXf& betas, BodyMesh& mesh);
// The vertices and joints only (normals left empty): what measuring a body reads.
BodyMesh evaluate_shape(const Model& model, const Eigen::VectorXf& betas);
void evaluate_batch_into(const Model& model, const std::vector<Eigen::VectorXf>& betas,
                         std::vector<BodyMesh>& meshes);

// Translates mesh and joints so the lowest vertex touches y = 0 (feet on the ground), as
// display and export want; returns the applied y offset.
float place_on_ground(BodyMesh& mesh);

// SMPL's 24 standard joint names, in SMPL's joint order (body/joint_names.hpp has the others).
const std::vector<std::string>& smpl_joint_names();

// The paper's mapping between the search box [0,1]^K and betas: beta = 6x - 3 (+-3 sigma).
Eigen::VectorXf betas_from_unit(const Eigen::VectorXd& x);
Eigen::VectorXd unit_from_betas(const Eigen::VectorXf& betas);

}  // namespace body
