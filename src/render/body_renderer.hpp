// Draws one body into the currently bound target: backdrop gradient, soft contact shadow on the
// floor, then the smooth-shaded body with key/fill/rim lighting. Owns its GL programs.
#pragma once

#include <glm/vec3.hpp>

#include "render/camera.hpp"
#include "render/gl_handles.hpp"
#include "render/mesh_gpu.hpp"

namespace render {

struct BodyStyle {
  glm::vec3 albedo{0.80f, 0.66f, 0.56f};
  glm::vec3 background_top{0.86f, 0.88f, 0.91f};
  glm::vec3 background_bottom{0.60f, 0.62f, 0.66f};
  float shadow_strength = 0.55f;
  bool shadow = true;
  // Closed, counter-clockwise meshes (SMPL family) lose nothing by culling back faces, and a
  // software rasterizer saves half its triangle work.
  bool cull_back_faces = true;
};

class BodyRenderer {
 public:
  BodyRenderer();  // compiles the embedded shaders; needs a current GL 3.3 context

  // Renders into whatever framebuffer is bound, over the viewport `width` x `height`.
  // An empty mesh draws only the backdrop.
  // Not const: it caches the backdrop image per size.
  void draw(const MeshGpu& mesh, const Camera& camera, int width, int height,
            const BodyStyle& style = {});

 private:
  void draw_backdrop(const BodyStyle& style) const;

  Program body_;
  Program background_;
  Program shadow_;
  VertexArray empty_vao_;  // core profile needs a bound VAO even for attribute-less draws
  Framebuffer backdrop_fbo_;
  Texture backdrop_texture_;
  int backdrop_width_ = 0;
  int backdrop_height_ = 0;
  glm::vec3 backdrop_top_{-1.0f};
  glm::vec3 backdrop_bottom_{-1.0f};
};

}  // namespace render
