// One grid cell's offscreen target: a multisampled colour + depth framebuffer that is resolved
// into a plain RGBA8 texture, which the UI shows as an image (smooth edges without a
// multisampled default framebuffer). With samples = 0 it renders straight into the texture.
#pragma once

#include <cstdint>
#include <vector>

#include "render/gl_handles.hpp"

namespace render {

class CellFramebuffer {
 public:
  CellFramebuffer() = default;
  CellFramebuffer(int width, int height, int samples);

  // Reallocates the attachments when the size or sample count changes (no-op otherwise).
  void resize(int width, int height, int samples);

  // Binds the drawing target and sets the viewport to the whole cell.
  void begin() const;
  // Resolves the multisampled image into texture() and binds framebuffer 0 again.
  void end() const;

  GLuint texture() const { return texture_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

  // RGBA8 pixels of the resolved texture, bottom row first (GL order).
  std::vector<std::uint8_t> read_pixels() const;

 private:
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
  Framebuffer draw_fbo_;  // multisampled (only when samples_ > 0)
  Renderbuffer colour_ms_;
  Renderbuffer depth_;
  Framebuffer resolve_fbo_;  // texture_ attached
  Texture texture_;
};

}  // namespace render
