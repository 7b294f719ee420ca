#include "spaces/photo_enhancement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spaces {

namespace {

constexpr float kLuma[3] = {0.2126f, 0.7152f, 0.0722f};

float luma(const std::array<float, 3>& c) {
  return kLuma[0] * c[0] + kLuma[1] * c[1] + kLuma[2] * c[2];
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

float clamp01(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}

}  // namespace

const std::string& photo_parameter_name(int i) {
  static const std::string names[kPhotoParameters] = {"brightness",
                                                      "contrast",
                                                      "saturation",
                                                      "shadows: cyan - red",
                                                      "shadows: magenta - green",
                                                      "shadows: yellow - blue",
                                                      "midtones: cyan - red",
                                                      "midtones: magenta - green",
                                                      "midtones: yellow - blue",
                                                      "highlights: cyan - red",
                                                      "highlights: magenta - green",
                                                      "highlights: yellow - blue"};
  if (i < 0 || i >= kPhotoParameters) throw std::out_of_range("photo parameter index");
  return names[i];
}

std::array<float, 12> photo_parameters(const Eigen::VectorXd& x) {
  if (x.size() != kPhotoParameters) {
    throw std::invalid_argument("a photo edit has 12 parameters, got " + std::to_string(x.size()));
  }
  std::array<float, 12> p{};
  for (int i = 0; i < kPhotoParameters; ++i) {
    p[static_cast<std::size_t>(i)] = static_cast<float>(std::clamp(2.0 * x[i] - 1.0, -1.0, 1.0));
  }
  return p;
}

std::array<float, 3> enhance_pixel(const std::array<float, 3>& rgb,
                                   const std::array<float, 12>& p) {
  std::array<float, 3> c = rgb;
  const float l = luma(c);
  const float w_shadow = 1.0f - smoothstep(0.0f, 0.5f, l);
  const float w_high = smoothstep(0.5f, 1.0f, l);
  const float w_mid = 1.0f - w_shadow - w_high;
  std::array<float, 3> shift{};
  for (int k = 0; k < 3; ++k) {
    shift[static_cast<std::size_t>(k)] = 0.25f * (w_shadow * p[static_cast<std::size_t>(3 + k)] +
                                                  w_mid * p[static_cast<std::size_t>(6 + k)] +
                                                  w_high * p[static_cast<std::size_t>(9 + k)]);
  }
  const float shift_luma = luma(shift);  // balance moves hue, not brightness
  for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k] + shift[k] - shift_luma);
  for (float& v : c) v = clamp01(v + 0.3f * p[0]);
  const float contrast = std::exp2(p[1]);
  for (float& v : c) v = clamp01((v - 0.5f) * contrast + 0.5f);
  const float l2 = luma(c);
  for (float& v : c) v = clamp01(l2 + (v - l2) * (1.0f + p[2]));
  return c;
}

void enhance_image(std::vector<std::uint8_t>& rgba, const std::array<float, 12>& p) {
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
    const std::array<float, 3> in{rgba[i] / 255.0f, rgba[i + 1] / 255.0f, rgba[i + 2] / 255.0f};
    const auto out = enhance_pixel(in, p);
    for (int k = 0; k < 3; ++k) {
      rgba[i + static_cast<std::size_t>(k)] =
          static_cast<std::uint8_t>(std::lround(out[static_cast<std::size_t>(k)] * 255.0f));
    }
  }
}

}  // namespace spaces
