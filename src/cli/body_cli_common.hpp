// Shared helpers of the body subcommands (export, measure, inspect): choosing the model and
// reading the shape from --betas or --x.
#pragma once

#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "cli/arg_parser.hpp"

namespace cli {

// argv with "-o" spelled "--output", so that a value list (--betas 1 -2 -o out.glb) ends at
// it: the shared parser reads values until the next "--" option. The strings live in `store`.
std::vector<char*> normalize_output_flag(int argc, char** argv, std::vector<std::string>& store);

// --model female|male|neutral|FILE (else the built-in neutral model), keeping --components N
// (default 10, or more if more betas/x values are given; 0 = all) shape components and
// --expressions N (default 0; SMPL-X only). Asking for more components or expressions than the
// file has is an ArgError.
body::Model load_body_model(const ArgParser& args);

// --components N larger than the model's component count is an error, not a silent clamp.
void check_component_count(const ArgParser& args, const body::Model& model);

// The largest |beta| accepted from the command line (standard deviations).
constexpr double kMaxAbsBeta = 10.0;

// --betas b1 b2 ... or --x x1 x2 ... (normalized [0,1], beta = 6x - 3); none = the mean body.
// Throws ArgError for both, for too many values, for --x outside [0, 1] or betas beyond
// +-kMaxAbsBeta.
Eigen::VectorXf read_betas(const ArgParser& args, const body::Model& model);

// --target name=value (repeatable; body/measurements.hpp names them): the betas nearest to
// `start` whose measurements meet the targets (body/measurement_solve.hpp); `start` itself
// without targets. Prints what was reached to stderr. Throws ArgError on a bad name or value
// and std::runtime_error naming the nearest reachable values when the targets are out of reach.
Eigen::VectorXf apply_targets(const ArgParser& args, const body::Model& model,
                              const Eigen::VectorXf& start);

// Number of values given with --betas or --x.
std::size_t shape_value_count(const ArgParser& args);

// Throws ArgError when `path` (the -o value) names a folder instead of a file, before any work.
void require_output_file(const std::string& path);

// "0.25, -1, 0" for messages.
std::string format_betas(const Eigen::VectorXf& betas);

}  // namespace cli
