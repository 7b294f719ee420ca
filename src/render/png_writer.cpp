#include "render/png_writer.hpp"

#include <cstring>
#include <stdexcept>

#include <stb_image_write.h>

namespace render {

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& pixels, bool bottom_up) {
  const size_t row = static_cast<size_t>(width) * 4;
  if (width <= 0 || height <= 0 || pixels.size() < row * static_cast<size_t>(height)) {
    throw std::runtime_error("cannot write " + path.string() + ": image buffer has wrong size");
  }
  std::vector<std::uint8_t> rows(pixels.begin(),
                                 pixels.begin() + static_cast<std::ptrdiff_t>(row) * height);
  if (bottom_up) {
    for (int y = 0; y < height; ++y) {
      std::memcpy(rows.data() + row * static_cast<size_t>(y),
                  pixels.data() + row * static_cast<size_t>(height - 1 - y), row);
    }
  }
  if (stbi_write_png(path.string().c_str(), width, height, 4, rows.data(), static_cast<int>(row)) ==
      0) {
    throw std::runtime_error("cannot write " + path.string() +
                             ": the directory is missing, not writable, or the disk is full");
  }
}

}  // namespace render
