// Stand-in geometry for renderer tests: a capsule-ish "body" (a stretched UV sphere) standing
// on the floor, so the renderer is testable without any body model.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace render_test {

struct TestMesh {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<std::uint32_t> indices;
  int vertex_count() const { return static_cast<int>(positions.size() / 3); }
};

// An ellipsoid with radii (rx, ry, rz) resting on y = 0.
inline TestMesh make_ellipsoid(float rx, float ry, float rz, int rings = 32, int segments = 48) {
  TestMesh m;
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= rings; ++i) {
    const float phi = pi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      const float theta = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
      const float x = std::sin(phi) * std::cos(theta);
      const float y = std::cos(phi);
      const float z = std::sin(phi) * std::sin(theta);
      m.positions.insert(m.positions.end(), {rx * x, ry * y + ry, rz * z});
      float nx = x / rx, ny = y / ry, nz = z / rz;
      const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
      m.normals.insert(m.normals.end(), {nx / len, ny / len, nz / len});
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a =
          static_cast<std::uint32_t>(i) * stride + static_cast<std::uint32_t>(j);
      const std::uint32_t b = a + stride;
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return m;
}

}  // namespace render_test
