// The generator of the default body models (assets/body_{female,male,neutral}.npz): template
// mannequin -> mesh -> rig -> populations -> PCA per model -> SMPL-layout .npz bytes. The three
// models share the template mesh (one topology) and rig; female and male are the PCA of each
// sex's population, neutral the PCA of both populations together (as SMPL's neutral model).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pose_correctives.hpp"
#include "survey_calibration.hpp"
#include "uv_layout.hpp"

namespace default_model {

struct GeneratorOptions {
  int population = 2000;  // bodies per sex
  // 18 keep each file under 5 MB (4.8 MB); with 16, fit-survey's 95th-percentile miss of the
  // men's waist was 3.4 cm (1.8 with 18, on 250 men).
  int components = 18;
  std::uint64_t seed = 20200724;  // fixed: the committed asset depends on it
  double grid_spacing = 0.006;    // marching tetrahedra grid, metres
  int threads = 2;                // grid and calibration; the result does not depend on it
  // Bodies of each sex measured per calibration round, and the rounds (survey_calibration.hpp).
  int calibration_sample = 240;
  int calibration_rounds = 3;
};

struct GeneratedModel {
  std::string name;  // "female", "male" or "neutral"
  // How far the population's girths are from their draw, per sex (neutral: both).
  std::vector<CalibrationReport> calibration_reports;
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> v_template;  // V x 3 (population mean)
  Eigen::Matrix<std::uint32_t, Eigen::Dynamic, 3, Eigen::RowMajor> faces;  // F x 3
  Eigen::MatrixXf shapedirs;       // 3V x K (row 3v + axis), betas ~ N(0, 1)
  Eigen::MatrixXf j_regressor;     // 55 x V (SMPL-X's joints)
  Eigen::MatrixXf weights;         // V x 55, at most 4 influences per vertex
  Eigen::VectorXf variance_share;  // K
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> joints;  // 55 x 3 on v_template
  std::vector<std::uint8_t> npz;                                    // the file's bytes
  // Diagnostics.
  double joint_fit_error = 0;             // max |J_regressor * template - constructed joint|, m
  int vertices_without_visible_bone = 0;  // the heat weights' (smplx_rig.hpp)
  UvLayout uv;                            // the texture layout (vt, ft)
  UvDistortion uv_distortion;
  PoseCorrectiveReport pose_correctives;
  std::vector<double> population_statures;  // m
};

// The three models, in the order female, male, neutral.
std::vector<GeneratedModel> generate_default_models(const GeneratorOptions& options = {});

// Names of the models in generate_default_models' order, and the asset file of each
// (relative to the source tree).
const std::vector<std::string>& default_model_names();
std::string default_model_asset(const std::string& name);

}  // namespace default_model
