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

void BodyRenderer::draw_backdrop(const BodyStyle& style) const {
  glUseProgram(background_.get());
  glUniform3fv(uniform(background_, "u_top"), 1, glm::value_ptr(style.background_top));
  glUniform3fv(uniform(background_, "u_bottom"), 1, glm::value_ptr(style.background_bottom));
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void BodyRenderer::draw(const MeshGpu& mesh, const Camera& camera, int width, int height,
                        const BodyStyle& style) {
  const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
  const glm::mat4 view = camera.view();
  const glm::mat4 projection = camera.projection(aspect);

  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);  // packed D24S8: one memset

  // Backdrop: into a single-sampled target it is copied from a cached image (a plain memory
  // copy for a software rasterizer), otherwise drawn.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  GLint target_samples = 0;
  glGetIntegerv(GL_SAMPLES, &target_samples);
  if (target_samples == 0 && width > 0 && height > 0) {
    GLint draw_fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
    if (backdrop_width_ != width || backdrop_height_ != height ||
        backdrop_top_ != style.background_top || backdrop_bottom_ != style.background_bottom) {
      backdrop_texture_ = Texture::create();
      glBindTexture(GL_TEXTURE_2D, backdrop_texture_.get());
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   nullptr);
      glBindTexture(GL_TEXTURE_2D, 0);
      backdrop_fbo_ = Framebuffer::create();
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, backdrop_fbo_.get());
      glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                             backdrop_texture_.get(), 0);
      draw_backdrop(style);
      backdrop_width_ = width;
      backdrop_height_ = height;
      backdrop_top_ = style.background_top;
      backdrop_bottom_ = style.background_bottom;
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo));
    }
    GLint read_fbo = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, backdrop_fbo_.get());
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fbo));
  } else {
    draw_backdrop(style);
  }

  glBindVertexArray(empty_vao_.get());
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
