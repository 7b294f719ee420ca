// The generator of the embedded default body model (assets/default_body.npz): template
// mannequin -> mesh -> rig -> population -> PCA -> SMPL-layout .npz bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace default_model {

struct GeneratorOptions {
  int population = 2000;
  int components = 16;
  std::uint64_t seed = 20200724;  // fixed: the committed asset depends on it
  double grid_spacing = 0.009;    // marching tetrahedra grid, metres
  int threads = 2;                // grid evaluation only; the result does not depend on it
};

struct GeneratedModel {
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> v_template;  // V x 3 (population mean)
  Eigen::Matrix<std::uint32_t, Eigen::Dynamic, 3, Eigen::RowMajor> faces;  // F x 3
  Eigen::MatrixXf shapedirs;       // 3V x K (row 3v + axis), betas ~ N(0, 1)
  Eigen::MatrixXf j_regressor;     // 24 x V
  Eigen::MatrixXf weights;         // V x 24, at most 4 influences per vertex
  Eigen::VectorXf variance_share;  // K
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> joints;  // 24 x 3 on v_template
  std::vector<std::uint8_t> npz;                                    // the file's bytes
  // Diagnostics.
  double joint_fit_error = 0;               // max |J_regressor * template - constructed joint|, m
  std::vector<double> population_statures;  // m
};

GeneratedModel generate_default_model(const GeneratorOptions& options = {});

}  // namespace default_model
