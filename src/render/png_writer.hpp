// PNG output of RGBA8 pixels (stb_image_write).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace render {

// `pixels`: width*height*4 bytes. bottom_up = true for glReadPixels order (rows are flipped).
// Throws std::runtime_error naming the file when it cannot be written.
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& pixels, bool bottom_up = true);

}  // namespace render
