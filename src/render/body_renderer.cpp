#include "render/body_renderer.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "render/shader_sources.hpp"

namespace render {

namespace {

GLint uniform(const Program& program, const char* name) {
  return glGetUniformLocation(program.get(), name);
}

}  // namespace

BodyRenderer::BodyRenderer()
    : body_(link_program(shader_source("body.vert"), shader_source("body.frag"), "body")),
      background_(link_program(shader_source("background.vert"), shader_source("background.frag"),
                               "background")),
      shadow_(link_program(shader_source("shadow.vert"), shader_source("shadow.frag"), "shadow")),
      empty_vao_(VertexArray::create()) {}

void BodyRenderer::draw(const MeshGpu& mesh, const Camera& camera, int width, int height,
                        const BodyStyle& style) const {
  const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
  const glm::mat4 view = camera.view();
  const glm::mat4 projection = camera.projection(aspect);

  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);

  // Backdrop.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(background_.get());
  glUniform3fv(uniform(background_, "u_top"), 1, glm::value_ptr(style.background_top));
  glUniform3fv(uniform(background_, "u_bottom"), 1, glm::value_ptr(style.background_bottom));
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);

  if (mesh.empty()) {
    glBindVertexArray(0);
    glUseProgram(0);
    return;
  }

  // Contact shadow on the floor under the feet.
  if (style.shadow) {
    const Footprint& fp = mesh.footprint();
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(shadow_.get());
    glUniformMatrix4fv(uniform(shadow_, "u_view"), 1, GL_FALSE, glm::value_ptr(view));
    glUniformMatrix4fv(uniform(shadow_, "u_projection"), 1, GL_FALSE, glm::value_ptr(projection));
    glUniform3fv(uniform(shadow_, "u_centre"), 1, glm::value_ptr(fp.centre));
    glUniform2f(uniform(shadow_, "u_radius"), fp.radius_x, fp.radius_z);
    glUniform1f(uniform(shadow_, "u_strength"), style.shadow_strength);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_BLEND);
  }
  glBindVertexArray(0);

  // The body.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(body_.get());
  glUniformMatrix4fv(uniform(body_, "u_view"), 1, GL_FALSE, glm::value_ptr(view));
  glUniformMatrix4fv(uniform(body_, "u_projection"), 1, GL_FALSE, glm::value_ptr(projection));
  glUniform3fv(uniform(body_, "u_albedo"), 1, glm::value_ptr(style.albedo));
  glUniform1f(uniform(body_, "u_floor_y"), mesh.bounds_min().y);
  if (style.cull_back_faces) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(mesh.counter_clockwise() ? GL_CCW : GL_CW);
  }
  mesh.draw();
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(0);
}

}  // namespace render
