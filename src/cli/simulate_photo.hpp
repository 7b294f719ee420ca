// `simulate --function photo`: the paper's photo application as a benchmark. A simulated
// person with a target edit of a picture in mind clicks through app::Session (the window's
// session logic, 3x3 grids as the window) and cannot tell apart cells whose colour differences to
// the target lie within a just-noticeable difference; the gap is the mean CIEDE2000 colour
// difference of the best edit chosen so far to the target, on the picture
// (spaces/photo_perception.hpp).
#pragma once

#include "cli/arg_parser.hpp"

namespace cli {

int run_photo_simulation(const ArgParser& args);

}  // namespace cli
