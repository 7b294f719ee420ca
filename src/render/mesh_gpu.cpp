#include "render/mesh_gpu.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <glm/glm.hpp>

namespace render {

void MeshGpu::upload(const float* positions, const float* normals, int vertex_count,
                     const std::uint32_t* indices, int index_count, const float* tints) {
  if (vertex_count <= 0 || index_count <= 0 || index_count % 3 != 0) {
    throw std::invalid_argument("MeshGpu::upload: empty mesh or index count not a multiple of 3");
  }
  for (int i = 0; i < index_count; ++i) {
    if (indices[i] >= static_cast<std::uint32_t>(vertex_count)) {
      throw std::invalid_argument("MeshGpu::upload: index out of range");
    }
  }
  vao_ = VertexArray::create();
  positions_ = Buffer::create();
  normals_ = Buffer::create();
  indices_ = Buffer::create();
  const auto bytes = static_cast<GLsizeiptr>(sizeof(float) * 3 * static_cast<size_t>(vertex_count));

  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, positions_.get());
  glBufferData(GL_ARRAY_BUFFER, bytes, positions, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, normals_.get());
  glBufferData(GL_ARRAY_BUFFER, bytes, normals, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  if (tints != nullptr) {
    tints_ = Buffer::create();
    glBindBuffer(GL_ARRAY_BUFFER, tints_.get());
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(sizeof(float) * static_cast<size_t>(vertex_count)), tints,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  } else {
    tints_ = Buffer();
    glDisableVertexAttribArray(2);  // the generic value, 0: skin
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(sizeof(std::uint32_t) * static_cast<size_t>(index_count)),
               indices, GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  vertex_count_ = vertex_count;
  index_count_ = index_count;
  measure(positions, vertex_count);

  // Signed volume (divergence theorem) tells the winding of a closed mesh's outward faces.
  double volume = 0.0;
  for (int t = 0; t + 2 < index_count; t += 3) {
    const float* a = positions + 3 * static_cast<size_t>(indices[t]);
    const float* b = positions + 3 * static_cast<size_t>(indices[t + 1]);
    const float* c = positions + 3 * static_cast<size_t>(indices[t + 2]);
    volume += static_cast<double>(a[0]) *
                  (static_cast<double>(b[1]) * c[2] - static_cast<double>(b[2]) * c[1]) +
              static_cast<double>(a[1]) *
                  (static_cast<double>(b[2]) * c[0] - static_cast<double>(b[0]) * c[2]) +
              static_cast<double>(a[2]) *
                  (static_cast<double>(b[0]) * c[1] - static_cast<double>(b[1]) * c[0]);
  }
  counter_clockwise_ = volume >= 0.0;
}

void MeshGpu::update(const float* positions, const float* normals, int vertex_count) {
  if (vertex_count != vertex_count_) {
    throw std::invalid_argument("MeshGpu::update: vertex count differs from upload()");
  }
  const auto bytes = static_cast<GLsizeiptr>(sizeof(float) * 3 * static_cast<size_t>(vertex_count));
  glBindBuffer(GL_ARRAY_BUFFER, positions_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, positions);
  glBindBuffer(GL_ARRAY_BUFFER, normals_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, normals);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  measure(positions, vertex_count);
}

void MeshGpu::draw() const {
  if (empty()) return;
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

void MeshGpu::measure(const float* p, int vertex_count) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  min_ = glm::vec3(inf);
  max_ = glm::vec3(-inf);
  for (int i = 0; i < vertex_count; ++i) {
    const glm::vec3 v(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    min_ = glm::min(min_, v);
    max_ = glm::max(max_, v);
  }
  // The contact shadow covers the lowest 12% of the body (feet and ankles).
  const float cut = min_.y + 0.12f * (max_.y - min_.y);
  glm::vec3 lo(inf), hi(-inf);
  for (int i = 0; i < vertex_count; ++i) {
    if (p[3 * i + 1] > cut) continue;
    lo = glm::min(lo, glm::vec3(p[3 * i], 0.0f, p[3 * i + 2]));
    hi = glm::max(hi, glm::vec3(p[3 * i], 0.0f, p[3 * i + 2]));
  }
  footprint_.centre = glm::vec3(0.5f * (lo.x + hi.x), min_.y, 0.5f * (lo.z + hi.z));
  footprint_.radius_x = std::max(0.6f * (hi.x - lo.x) + 0.08f, 0.1f);
  footprint_.radius_z = std::max(0.6f * (hi.z - lo.z) + 0.08f, 0.1f);
}

}  // namespace render
