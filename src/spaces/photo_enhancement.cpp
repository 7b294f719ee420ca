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

float clamp01(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}

// What +-1 of each parameter does: a strong edit a photographer might still keep, not an
// effect (the session's first grid spans most of the range, and a grid of casts and clipped
// skies helps nobody choose). The GPU's shaders/photo.frag uses the same numbers.
// Colour balance: the largest shift of a channel (of [0,1]) in its tone band.
constexpr float kBalanceShift = 0.12f;
// Brightness: a gamma curve (mid-grey 0.5 to 0.63 or 0.35 at +-1), which never clips.
constexpr float kBrightnessLog2Gamma = 0.6f;
// Contrast: the slope around mid-grey, 2^(0.6 p) (x1.5 or x0.66).
constexpr float kContrastLog2Slope = 0.6f;
// Saturation: the chroma factor 1 + 0.5 p (x1.5 or x0.5).
constexpr float kSaturationRange = 0.5f;

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
  // Tone first, colour balance last: a balance applied before a desaturating or flattening
  // edit shrank with it (at saturation and contrast -100 a colour cast was a fifth as strong),
  // so one slider's meaning depended on two others and a grid's cells went alike there.
  const float gamma = std::exp2(-kBrightnessLog2Gamma * p[0]);
  for (float& v : c) v = std::pow(v, gamma);
  const float contrast = std::exp2(kContrastLog2Slope * p[1]);
  for (float& v : c) v = clamp01((v - 0.5f) * contrast + 0.5f);
  const float l = luma(c);
  for (float& v : c) v = clamp01(l + (v - l) * (1.0f + kSaturationRange * p[2]));
  // Tone bands as quadratic Bernstein weights of the luma (they sum to 1): a bright sky at
  // luma 0.6 is a third highlights. Bands cut at 0.5 by smoothsteps gave it a tenth, and the
  // highlight sliders barely changed a landscape (4 Delta E over their whole range).
  const float w_shadow = (1.0f - l) * (1.0f - l);
  const float w_high = l * l;
  const float w_mid = 1.0f - w_shadow - w_high;
  std::array<float, 3> shift{};
  for (int k = 0; k < 3; ++k) {
    shift[static_cast<std::size_t>(k)] =
        kBalanceShift *
        (w_shadow * p[static_cast<std::size_t>(3 + k)] +
         w_mid * p[static_cast<std::size_t>(6 + k)] + w_high * p[static_cast<std::size_t>(9 + k)]);
  }
  // Luminosity preserved (Photoshop's default for its colour balance): the balance moves hue,
  // not brightness, so it stays visible on bright pixels, where a shift upwards would clip.
  const float shift_luma = luma(shift);
  for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k] + shift[k] - shift_luma);
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
