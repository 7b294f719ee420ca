#include "render/png_writer.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include <stb_image_write.h>

#include "util/atomic_file.hpp"

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
  // Encode in memory, then write through the atomic writer: a full disk or a missing folder
  // leaves an existing PNG untouched and reports the reason.
  std::string encoded;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (stbi_write_png_to_func(append, &encoded, width, height, 4, rows.data(),
                             static_cast<int>(row)) == 0) {
    throw std::runtime_error("cannot write " + path.string() + ": PNG encoding failed");
  }
  util::write_file_atomically(path, encoded);
}

}  // namespace render
