#include "spaces/photo_image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "util/file_read.hpp"

namespace spaces {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxEdge = 16384;
constexpr long long kMaxPixels = 64LL * 1024 * 1024;

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

// Deterministic value noise in [0,1] (integer hash, bilinear).
float hash01(int x, int y) {
  std::uint32_t h =
      static_cast<std::uint32_t>(x) * 374761393u + static_cast<std::uint32_t>(y) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return static_cast<float>((h ^ (h >> 16)) & 0xffffu) / 65535.0f;
}

float value_noise(float x, float y) {
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(xi), fy = y - static_cast<float>(yi);
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const float a = hash01(xi, yi), b = hash01(xi + 1, yi), c = hash01(xi, yi + 1),
              d = hash01(xi + 1, yi + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

float fractal(float x, float y) {
  return 0.5f * value_noise(x, y) + 0.25f * value_noise(2 * x, 2 * y) +
         0.125f * value_noise(4 * x, 4 * y) + 0.125f * value_noise(8 * x, 8 * y);
}

struct Rgb {
  float r, g, b;
};

Rgb mix(Rgb a, Rgb b, float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

void write_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<std::size_t>(size));
}

}  // namespace

Image load_image(const fs::path& path) {
  // Read through the regular-file reader first: stb would block forever on a pipe and read a
  // device without end.
  constexpr std::size_t kMaxFileBytes = 256u << 20;
  std::string bytes;
  try {
    bytes = util::read_regular_file(path, kMaxFileBytes);
  } catch (const util::FileReadError& e) {
    throw std::runtime_error(e.what());
  }
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    throw std::runtime_error(path.string() + ": too large for an image");
  }
  const auto* data_in = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (stbi_info_from_memory(data_in, length, &w, &h, &channels) == 0) {
    const char* why = stbi_failure_reason();
    throw std::runtime_error(path.string() + ": not a PNG or JPEG image we can read (" +
                             (why != nullptr ? why : "unknown format") + ")");
  }
  if (w < 1 || h < 1 || w > kMaxEdge || h > kMaxEdge ||
      static_cast<long long>(w) * h > kMaxPixels) {
    throw std::runtime_error(path.string() + ": image of " + std::to_string(w) + "x" +
                             std::to_string(h) + " pixels is too large (at most " +
                             std::to_string(kMaxEdge) + " per side, 64 Mpixels)");
  }
  unsigned char* data = stbi_load_from_memory(data_in, length, &w, &h, &channels, 4);
  if (data == nullptr) {
    const char* why = stbi_failure_reason();
    throw std::runtime_error(path.string() + ": cannot decode the image (" +
                             (why != nullptr ? why : "unknown error") + ")");
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(data, data + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(data);
  return image;
}

Image default_photo() {
  Image img;
  img.width = 960;
  img.height = 640;
  img.rgba.resize(static_cast<std::size_t>(img.width) * img.height * 4);
  const float W = static_cast<float>(img.width), H = static_cast<float>(img.height);
  const float horizon = 0.58f;  // lake line, fraction of the height
  auto far_ridge = [](float u) {
    return 0.40f - 0.07f * std::sin(u * 7.0f + 0.6f) - 0.05f * std::sin(u * 17.0f + 2.0f) -
           0.04f * fractal(u * 6.0f, 0.5f);
  };
  auto near_ridge = [](float u) {
    return 0.50f - 0.05f * std::sin(u * 4.0f + 2.4f) - 0.02f * std::sin(u * 11.0f);
  };
  const Rgb sky_top{0.18f, 0.36f, 0.70f}, sky_low{0.98f, 0.80f, 0.60f};
  const Rgb sun{1.0f, 0.97f, 0.85f};
  const float sun_u = 0.74f, sun_v = 0.27f, sun_r = 0.045f;
  auto scene = [&](float u, float v) -> Rgb {
    // Sky with the sun and its glow.
    Rgb c = mix(sky_top, sky_low, std::pow(v / horizon, 1.6f));
    const float du = (u - sun_u) * W / H, dv = v - sun_v;
    const float d = std::sqrt(du * du + dv * dv);
    c = mix(c, sun, 0.55f * std::exp(-d * 9.0f));
    if (d < sun_r) c = sun;
    // Clouds.
    const float cloud = fractal(u * 5.0f, v * 14.0f);
    if (v < 0.33f) c = mix(c, Rgb{0.97f, 0.95f, 0.96f}, std::max(0.0f, cloud - 0.55f) * 2.2f);
    // Far mountains (blue, hazy), then near hills (green) with a meadow texture.
    if (v > far_ridge(u)) {
      const float depth = (v - far_ridge(u)) * 6.0f;
      const float rock = fractal(u * 30.0f, v * 30.0f);
      c = mix(Rgb{0.50f, 0.55f, 0.70f}, Rgb{0.28f, 0.33f, 0.48f}, depth + 0.3f * (rock - 0.5f));
      // Snow on the high peaks only, thinning out downhill.
      const float snow_line = 0.335f + 0.02f * rock;
      if (v < snow_line && v < far_ridge(u) + 0.05f) c = mix(c, Rgb{0.93f, 0.94f, 0.98f}, 0.85f);
    }
    if (v > near_ridge(u)) {
      const float grass = fractal(u * 60.0f, v * 90.0f);
      c = mix(Rgb{0.38f, 0.58f, 0.20f}, Rgb{0.12f, 0.30f, 0.10f}, (v - near_ridge(u)) * 7.0f);
      c = mix(c, Rgb{0.65f, 0.70f, 0.25f}, (grass - 0.5f) * 0.8f);
    }
    return c;
  };
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / W;
      const float v = (static_cast<float>(y) + 0.5f) / H;
      Rgb c;
      if (v < horizon) {
        c = scene(u, v);
        // A house: cream walls, a red roof, a dark door.
        const float hx = 0.30f, hw = 0.07f, wall_top = 0.485f, base = 0.545f;
        if (u > hx && u < hx + hw && v > wall_top && v < base) c = {0.92f, 0.86f, 0.70f};
        const float roof = wall_top - 0.04f * (1.0f - std::fabs((u - hx - hw / 2) / (hw * 0.6f)));
        if (u > hx - 0.01f && u < hx + hw + 0.01f && v > roof && v <= wall_top) {
          c = {0.72f, 0.12f, 0.10f};
        }
        if (u > hx + 0.028f && u < hx + 0.042f && v > 0.515f && v < base) c = {0.20f, 0.12f, 0.08f};
        // Dark fir trees.
        for (int t = 0; t < 7; ++t) {
          const float tu = 0.08f + 0.11f * static_cast<float>(t) + 0.02f * hash01(t, 3);
          const float tb = 0.56f, th = 0.08f + 0.04f * hash01(t, 7);
          const float half = 0.018f * (v - (tb - th)) / th;
          if (v > tb - th && v < tb && std::fabs(u - tu) < half) c = {0.05f, 0.18f, 0.08f};
        }
      } else {
        // The lake mirrors the scene, darker, with ripples.
        const float mirror_v = 2.0f * horizon - v;
        const float ripple = 0.004f * std::sin(v * 420.0f + 3.0f * fractal(u * 8.0f, v * 30.0f));
        c = scene(std::clamp(u + ripple, 0.0f, 1.0f), std::max(0.0f, mirror_v));
        c = mix(c, Rgb{0.04f, 0.12f, 0.20f}, 0.35f + (v - horizon) * 1.2f);
      }
      const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 4;
      img.rgba[i] = static_cast<std::uint8_t>(std::lround(std::clamp(c.r, 0.0f, 1.0f) * 255));
      img.rgba[i + 1] = static_cast<std::uint8_t>(std::lround(std::clamp(c.g, 0.0f, 1.0f) * 255));
      img.rgba[i + 2] = static_cast<std::uint8_t>(std::lround(std::clamp(c.b, 0.0f, 1.0f) * 255));
      img.rgba[i + 3] = 255;
    }
  }
  return img;
}

std::string encode_image(const Image& image, const fs::path& path_for_format) {
  const std::string ext = lower_extension(path_for_format);
  std::string bytes;
  int ok = 0;
  if (ext == ".png") {
    ok = stbi_write_png_to_func(&write_to_string, &bytes, image.width, image.height, 4,
                                image.rgba.data(), image.width * 4);
  } else if (ext == ".jpg" || ext == ".jpeg") {
    // JPEG has no alpha: drop it.
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
    for (std::size_t i = 0, j = 0; j < rgb.size(); i += 4, j += 3) {
      std::memcpy(&rgb[j], &image.rgba[i], 3);
    }
    ok = stbi_write_jpg_to_func(&write_to_string, &bytes, image.width, image.height, 3, rgb.data(),
                                92);
  } else {
    throw std::runtime_error(path_for_format.string() +
                             ": choose a file name ending in .png, .jpg or .jpeg");
  }
  if (ok == 0) throw std::runtime_error(path_for_format.string() + ": image encoding failed");
  return bytes;
}

}  // namespace spaces
