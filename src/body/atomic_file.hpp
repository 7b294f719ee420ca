// The body library writes files through the project's one atomic writer (util/atomic_file.hpp);
// these names keep existing callers (the glTF exporter) unchanged.
#pragma once

#include "util/atomic_file.hpp"

namespace body {

using util::FileWriteError;
using util::write_all;
using util::write_file_atomically;

}  // namespace body
