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
// (default 10, or more if more betas/x values are given; 0 = all).
body::Model load_body_model(const ArgParser& args);

// --betas b1 b2 ... or --x x1 x2 ... (normalized [0,1], beta = 6x - 3); none = the mean body.
// Throws ArgError for both, for too many values, or for --x outside [0, 1].
Eigen::VectorXf read_betas(const ArgParser& args, const body::Model& model);

// Number of values given with --betas or --x.
std::size_t shape_value_count(const ArgParser& args);

// "0.25, -1, 0" for messages.
std::string format_betas(const Eigen::VectorXf& betas);

}  // namespace cli
