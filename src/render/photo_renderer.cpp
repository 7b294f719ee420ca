#include "render/photo_renderer.hpp"

#include <algorithm>
#include <stdexcept>

#include "render/shader_sources.hpp"

namespace render {

PhotoRenderer::PhotoRenderer(int width, int height, const std::vector<std::uint8_t>& rgba)
    : width_(width), height_(height) {
  if (width < 1 || height < 1 ||
      rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    throw std::invalid_argument("PhotoRenderer: pixel data does not match the image size");
  }
  program_ = link_program(shader_source("background.vert"), shader_source("photo.frag"), "photo");
  texture_ = Texture::create();
  vao_ = VertexArray::create();
  glBindTexture(GL_TEXTURE_2D, texture_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  check_gl("PhotoRenderer");
}

void PhotoRenderer::draw(const std::array<float, 12>& params, int viewport_w,
                         int viewport_h) const {
  // Fill the viewport with the photo, keeping its aspect: a square grid cell shows the middle
  // of a landscape picture edge to edge (a colour edit is the same everywhere, and grey bars
  // above and below took a third of a cell), the previews in the photo's aspect all of it.
  const float image_aspect = static_cast<float>(width_) / static_cast<float>(height_);
  const float view_aspect =
      static_cast<float>(std::max(1, viewport_w)) / static_cast<float>(std::max(1, viewport_h));
  float x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  if (image_aspect < view_aspect) {
    const float h = view_aspect / image_aspect;
    y0 = 0.5f - 0.5f * h;
    y1 = 0.5f + 0.5f * h;
  } else {
    const float w = image_aspect / view_aspect;
    x0 = 0.5f - 0.5f * w;
    x1 = 0.5f + 0.5f * w;
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glUseProgram(program_.get());
  glUniform1fv(glGetUniformLocation(program_.get(), "u_p"), 12, params.data());
  glUniform4f(glGetUniformLocation(program_.get(), "u_rect"), x0, y0, x1, y1);
  glUniform3f(glGetUniformLocation(program_.get(), "u_backdrop"), 0.16f, 0.17f, 0.19f);
  glUniform1i(glGetUniformLocation(program_.get(), "u_image"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_.get());
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
}

}  // namespace render
