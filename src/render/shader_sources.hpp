// GLSL sources from shaders/, compiled into the binary at build time so the tool runs from
// any directory.
#pragma once

#include <string>

namespace render {

// `name` is a file name in shaders/, e.g. "body.vert"; throws std::out_of_range if unknown.
const std::string& shader_source(const std::string& name);

}  // namespace render
