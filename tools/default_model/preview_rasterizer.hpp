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
// With `corner_uv` (three texture coordinates per triangle, in [0, 1]^2) the surface shows a
// checkerboard of `checks` x `checks` squares on the texture, for judging a UV layout.
void draw_mesh(Image& image, int x0, int y0, int w, int h,
               const std::vector<Eigen::Vector3f>& vertices,
               const std::vector<std::uint32_t>& triangles, View view,
               const Eigen::Vector3f& centre, float pixels_per_metre,
               const std::vector<Eigen::Vector2f>* corner_uv = nullptr, int checks = 32);

// The texture layout itself in the square (x0, y0, size): every triangle filled with its
// chart's colour (`chart` per triangle) on a grey ground, edges darker.
void draw_uv_layout(Image& image, int x0, int y0, int size,
                    const std::vector<Eigen::Vector2f>& corner_uv, const std::vector<int>& chart);

void write_png(const Image& image, const std::string& path);

}  // namespace default_model
