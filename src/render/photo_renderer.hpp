// Draws a photo with the 12-parameter colour enhancement (shaders/photo.frag) into the bound
// target, filling the viewport (cropped to its aspect, never letterboxed). Owns the image texture
// (mipmapped, so a large photo shrinks into a small cell without shimmer) and the program.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/gl_handles.hpp"

namespace render {

class PhotoRenderer {
 public:
  // `rgba`: width*height*4 bytes, top row first. Needs a current GL 3.3 context.
  PhotoRenderer(int width, int height, const std::vector<std::uint8_t>& rgba);
  // `params`: each in [-1, 1]; see shaders/photo.frag.
  void draw(const std::array<float, 12>& params, int viewport_w, int viewport_h) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_;
  int height_;
  Program program_;
  Texture texture_;
  VertexArray vao_;
};

}  // namespace render
