// Images for the photo space: reading PNG/JPEG (Debian's stb), the built-in default picture
// (drawn procedurally by this project, so it may ship with it), and encoding for export.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace spaces {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width*height*4, top row first
};

// PNG or JPEG (anything stb_image reads). Checks the header's size before decoding; throws
// std::runtime_error naming the file and the problem.
Image load_image(const std::filesystem::path& path);

// A landscape drawn from code (sky, sun, mountains, a house, trees, a lake): shadows,
// midtones, highlights and saturated colours for the enhancement to work on. 960x640.
Image default_photo();

// PNG, or JPEG (quality 92) when the extension is .jpg/.jpeg; throws on any other extension.
std::string encode_image(const Image& image, const std::filesystem::path& path_for_format);

}  // namespace spaces
