#include "preview_rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <stb_image_write.h>
#include <Eigen/Geometry>

#include "util/atomic_file.hpp"

namespace default_model {

void draw_mesh(Image& image, int x0, int y0, int w, int h,
               const std::vector<Eigen::Vector3f>& vertices,
               const std::vector<std::uint32_t>& triangles, View view,
               const Eigen::Vector3f& centre, float pixels_per_metre,
               const std::vector<Eigen::Vector2f>* corner_uv, int checks) {
  const std::size_t V = vertices.size();
  // Camera axes: screen right, screen up, towards the viewer.
  Eigen::Vector3f right(1, 0, 0), up(0, 1, 0), toward(0, 0, 1);
  if (view == View::kSide) {  // the subject's left side, facing the left of the image
    right = {0, 0, -1};
    toward = {1, 0, 0};
  } else if (view == View::kBack) {
    right = {-1, 0, 0};
    toward = {0, 0, -1};
  }
  std::vector<Eigen::Vector3f> normals(V, Eigen::Vector3f::Zero());
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const auto &a = vertices[triangles[t]], &b = vertices[triangles[t + 1]],
               &c = vertices[triangles[t + 2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals[triangles[t + k]] += n;
  }
  for (auto& n : normals) n.normalize();
  std::vector<Eigen::Vector3f> screen(V);
  for (std::size_t i = 0; i < V; ++i) {
    const Eigen::Vector3f d = vertices[i] - centre;
    screen[i] = {x0 + 0.5f * w + pixels_per_metre * d.dot(right),
                 y0 + 0.5f * h - pixels_per_metre * d.dot(up), d.dot(toward)};
  }
  std::vector<float> depth(static_cast<std::size_t>(w) * h,
                           -std::numeric_limits<float>::infinity());
  const Eigen::Vector3f light = (0.35f * right + 0.5f * up + toward).normalized();
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const std::uint32_t i0 = triangles[t], i1 = triangles[t + 1], i2 = triangles[t + 2];
    const Eigen::Vector3f &p0 = screen[i0], &p1 = screen[i1], &p2 = screen[i2];
    const float area =
        (p1.x() - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (p1.y() - p0.y());
    if (std::abs(area) < 1e-12f) continue;
    const bool back_facing = area > 0;  // screen y points down
    const int xa = std::max(x0, static_cast<int>(std::floor(std::min({p0.x(), p1.x(), p2.x()}))));
    const int xb =
        std::min(x0 + w - 1, static_cast<int>(std::ceil(std::max({p0.x(), p1.x(), p2.x()}))));
    const int ya = std::max(y0, static_cast<int>(std::floor(std::min({p0.y(), p1.y(), p2.y()}))));
    const int yb =
        std::min(y0 + h - 1, static_cast<int>(std::ceil(std::max({p0.y(), p1.y(), p2.y()}))));
    for (int y = ya; y <= yb; ++y)
      for (int x = xa; x <= xb; ++x) {
        const float px = x + 0.5f, py = y + 0.5f;
        const float w0 = ((p1.x() - px) * (p2.y() - py) - (p2.x() - px) * (p1.y() - py)) / area;
        const float w1 = ((p2.x() - px) * (p0.y() - py) - (p0.x() - px) * (p2.y() - py)) / area;
        const float w2 = 1.0f - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const float z = w0 * p0.z() + w1 * p1.z() + w2 * p2.z();
        float& zb = depth[static_cast<std::size_t>(y - y0) * w + (x - x0)];
        if (z <= zb) continue;
        zb = z;
        Eigen::Vector3f n = (w0 * normals[i0] + w1 * normals[i1] + w2 * normals[i2]).normalized();
        float shade = 0.18f + 0.82f * std::max(0.0f, n.dot(light));
        float r = 0.86f * shade, g = 0.74f * shade, b = 0.64f * shade;
        if (corner_uv != nullptr) {
          const Eigen::Vector2f uv =
              w0 * (*corner_uv)[t] + w1 * (*corner_uv)[t + 1] + w2 * (*corner_uv)[t + 2];
          const int cu = static_cast<int>(std::floor(uv.x() * checks));
          const int cv = static_cast<int>(std::floor(uv.y() * checks));
          const bool dark = ((cu + cv) & 1) != 0;
          // Two hues a few squares wide, so that a stretched or turned square shows.
          const bool band = ((cu / 4 + cv / 4) & 1) != 0;
          r = (dark ? 0.15f : 0.95f) * shade;
          g = (dark ? 0.15f : (band ? 0.75f : 0.95f)) * shade;
          b = (dark ? (band ? 0.45f : 0.15f) : 0.95f) * shade;
        }
        if (back_facing) r = 0.9f, g = 0.1f, b = 0.1f;  // inside showing: a defect
        std::uint8_t* px8 = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
        px8[0] = static_cast<std::uint8_t>(std::clamp(r, 0.0f, 1.0f) * 255);
        px8[1] = static_cast<std::uint8_t>(std::clamp(g, 0.0f, 1.0f) * 255);
        px8[2] = static_cast<std::uint8_t>(std::clamp(b, 0.0f, 1.0f) * 255);
      }
  }
}

void draw_uv_layout(Image& image, int x0, int y0, int size,
                    const std::vector<Eigen::Vector2f>& corner_uv, const std::vector<int>& chart) {
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) {
      std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      p[0] = p[1] = p[2] = 60;
    }
  for (std::size_t t = 0; 3 * t + 2 < corner_uv.size(); ++t) {
    Eigen::Vector2f q[3];
    for (int k = 0; k < 3; ++k)
      q[k] = {x0 + corner_uv[3 * t + k].x() * size, y0 + (1.0f - corner_uv[3 * t + k].y()) * size};
    const float area = (q[1].x() - q[0].x()) * (q[2].y() - q[0].y()) -
                       (q[2].x() - q[0].x()) * (q[1].y() - q[0].y());
    if (std::abs(area) < 1e-9f) continue;
    // A colour per chart from a hash of its number.
    const unsigned hsh = static_cast<unsigned>(chart[t]) * 2654435761u;
    const std::uint8_t col[3] = {static_cast<std::uint8_t>(110 + (hsh >> 8) % 140),
                                 static_cast<std::uint8_t>(110 + (hsh >> 16) % 140),
                                 static_cast<std::uint8_t>(110 + (hsh >> 24) % 140)};
    const int xa =
        std::max(x0, static_cast<int>(std::floor(std::min({q[0].x(), q[1].x(), q[2].x()}))));
    const int xb = std::min(x0 + size - 1,
                            static_cast<int>(std::ceil(std::max({q[0].x(), q[1].x(), q[2].x()}))));
    const int ya =
        std::max(y0, static_cast<int>(std::floor(std::min({q[0].y(), q[1].y(), q[2].y()}))));
    const int yb = std::min(y0 + size - 1,
                            static_cast<int>(std::ceil(std::max({q[0].y(), q[1].y(), q[2].y()}))));
    for (int y = ya; y <= yb; ++y)
      for (int x = xa; x <= xb; ++x) {
        const float px = x + 0.5f, py = y + 0.5f;
        const float w0 =
            ((q[1].x() - px) * (q[2].y() - py) - (q[2].x() - px) * (q[1].y() - py)) / area;
        const float w1 =
            ((q[2].x() - px) * (q[0].y() - py) - (q[0].x() - px) * (q[2].y() - py)) / area;
        const float w2 = 1.0f - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const bool edge = std::min({w0, w1, w2}) < 0.06f;
        std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
        for (int c = 0; c < 3; ++c)
          p[c] = area > 0 ? (c == 0 ? 255 : 0)  // flipped (image y runs down): red
                          : static_cast<std::uint8_t>(edge ? col[c] * 0.6f : col[c]);
      }
  }
}

void write_png(const Image& image, const std::string& path) {
  std::string encoded;  // encoded in memory, then written by the project's atomic writer
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 3, image.rgb.data(),
                              3 * image.width))
    throw std::runtime_error("cannot encode " + path);
  util::write_file_atomically(path, encoded);
}

}  // namespace default_model
