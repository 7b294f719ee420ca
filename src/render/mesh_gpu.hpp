// A triangle mesh on the GPU: positions and normals (float3 each) plus a fixed index buffer,
// and optionally a fixed tint per vertex (0 skin, 1 eye white, 2 iris: body::EyePart).
// Positions/normals change every frame while bodies morph; update() rewrites them in place
// with glBufferSubData, the topology never changes after upload().
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "render/gl_handles.hpp"

namespace render {

// The part of the mesh near the floor, for the contact shadow: an ellipse on y = floor_y.
struct Footprint {
  glm::vec3 centre{0.0f};  // x, z centre of the lowest part of the mesh (y = floor height)
  float radius_x = 0.2f;
  float radius_z = 0.15f;
};

class MeshGpu {
 public:
  MeshGpu() = default;

  // positions/normals: vertex_count * 3 floats; indices: index_count (triangles); tints:
  // vertex_count floats, or null for skin everywhere.
  void upload(const float* positions, const float* normals, int vertex_count,
              const std::uint32_t* indices, int index_count, const float* tints = nullptr);
  // Same vertex count as upload(); the topology stays.
  void update(const float* positions, const float* normals, int vertex_count);

  void draw() const;

  bool empty() const { return index_count_ == 0; }
  int vertex_count() const { return vertex_count_; }
  const glm::vec3& bounds_min() const { return min_; }
  const glm::vec3& bounds_max() const { return max_; }
  const Footprint& footprint() const { return footprint_; }
  // Whether the outward faces wind counter-clockwise (positive signed volume at upload).
  bool counter_clockwise() const { return counter_clockwise_; }

 private:
  void measure(const float* positions, int vertex_count);

  VertexArray vao_;
  Buffer positions_;
  Buffer normals_;
  Buffer tints_;
  Buffer indices_;
  int vertex_count_ = 0;
  int index_count_ = 0;
  glm::vec3 min_{0.0f};
  glm::vec3 max_{0.0f};
  Footprint footprint_;
  bool counter_clockwise_ = true;
};

}  // namespace render
