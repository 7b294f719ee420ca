// `simulate --function body`: the product's own job as a benchmark. A simulated person with a
// target body in mind clicks through app::Session (the window's session logic) and cannot
// tell apart bodies within a just-noticeable difference; the gap is the RMS vertex distance
// (mm) of the best body chosen so far to the target.
#pragma once

#include "cli/arg_parser.hpp"

namespace cli {

int run_body_simulation(const ArgParser& args);

}  // namespace cli
