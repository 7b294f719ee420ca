// The photo colour enhancement of the paper's first application (12 parameters: brightness,
// contrast, saturation, and colour balance cyan-red / magenta-green / yellow-blue for shadows,
// midtones and highlights), on the CPU. The GPU runs the same formula (shaders/photo.frag) for
// the cells; exports use this one, at full resolution and without a GL context.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace spaces {

constexpr int kPhotoParameters = 12;

// Parameter i's name, e.g. "shadows: cyan - red".
const std::string& photo_parameter_name(int i);

// x in [0,1]^12 -> parameters in [-1,1] (x = 0.5 leaves the photo unchanged).
std::array<float, 12> photo_parameters(const Eigen::VectorXd& x);

// One pixel, channels in [0,1].
std::array<float, 3> enhance_pixel(const std::array<float, 3>& rgb, const std::array<float, 12>& p);

// RGBA8 pixels (alpha kept) enhanced in place.
void enhance_image(std::vector<std::uint8_t>& rgba, const std::array<float, 12>& p);

}  // namespace spaces
