#include "render/cell_framebuffer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace render {

namespace {

void require_complete(const char* which) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(std::string("cell framebuffer (") + which + ") incomplete, status " +
                             std::to_string(status));
  }
}

}  // namespace

CellFramebuffer::CellFramebuffer(int width, int height, int samples) {
  resize(width, height, samples);
}

void CellFramebuffer::resize(int width, int height, int samples) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("cell framebuffer size must be > 0");
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::clamp(samples, 0, std::max(0, static_cast<int>(max_samples)));
  if (width == width_ && height == height_ && samples == samples_ && texture_) return;
  width_ = width;
  height_ = height;
  samples_ = samples;
  linear_ = false;

  texture_ = Texture::create();
  glBindTexture(GL_TEXTURE_2D, texture_.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);

  if (samples_ > 0) {
    depth_ = Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, depth_.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH24_STENCIL8, width, height);
  }

  depth_single_ = Renderbuffer::create();
  glBindRenderbuffer(GL_RENDERBUFFER, depth_single_.get());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
  resolve_fbo_ = Framebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_.get(), 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                            depth_single_.get());
  if (samples_ == 0) {
    depth_.reset();
    colour_ms_.reset();
    draw_fbo_.reset();
  }
  require_complete("resolve");

  if (samples_ > 0) {
    colour_ms_ = Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, colour_ms_.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width, height);
    draw_fbo_ = Framebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              colour_ms_.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              depth_.get());
    require_complete("multisampled");
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CellFramebuffer::begin(int region_w, int region_h, bool multisample) const {
  const bool ms = multisample && samples_ > 0;
  glBindFramebuffer(GL_FRAMEBUFFER, ms ? draw_fbo_.get() : resolve_fbo_.get());
  glViewport(0, 0, std::clamp(region_w, 1, width_), std::clamp(region_h, 1, height_));
}

void CellFramebuffer::end(int region_w, int region_h, bool multisample) const {
  if (multisample && samples_ > 0) {
    const int w = std::clamp(region_w, 1, width_);
    const int h = std::clamp(region_h, 1, height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_.get());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.get());
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CellFramebuffer::region_uv(int region_w, int region_h, float uv0[2], float uv1[2]) const {
  const float u = width_ > 0 ? static_cast<float>(std::clamp(region_w, 1, width_)) / width_ : 1.0f;
  const float v =
      height_ > 0 ? static_cast<float>(std::clamp(region_h, 1, height_)) / height_ : 1.0f;
  uv0[0] = 0.0f;
  uv0[1] = v;
  uv1[0] = u;
  uv1[1] = 0.0f;
}

void CellFramebuffer::set_linear_filtering(bool linear) {
  if (linear == linear_ || !texture_) return;
  linear_ = linear;
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glBindTexture(GL_TEXTURE_2D, texture_.get());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glBindTexture(GL_TEXTURE_2D, 0);
}

std::vector<std::uint8_t> CellFramebuffer::read_pixels() const {
  std::vector<std::uint8_t> pixels(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return pixels;
}

}  // namespace render
