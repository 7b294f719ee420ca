// A tiny software rasteriser for looking at meshes without GL: orthographic views, z-buffer,
// smooth Lambert shading, PNG output. Used by the generator's --preview option and for the
// contact sheet fallback; not part of the model itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace default_model {

enum class View { kFront, kSide, kBack };

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first
  Image(int w, int h, std::uint8_t grey = 255) : width(w), height(h), rgb(3 * w * h, grey) {}
};

// Draws the mesh into the rectangle (x0, y0, w, h) of `image`; the world point `centre` maps
// to the rectangle's centre and `pixels_per_metre` sets the scale.
void draw_mesh(Image& image, int x0, int y0, int w, int h,
               const std::vector<Eigen::Vector3f>& vertices,
               const std::vector<std::uint32_t>& triangles, View view,
               const Eigen::Vector3f& centre, float pixels_per_metre);

void write_png(const Image& image, const std::string& path);

}  // namespace default_model
