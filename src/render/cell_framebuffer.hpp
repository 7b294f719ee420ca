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
  void begin() const { begin(width_, height_, true); }
  // Resolves the multisampled image into texture() and binds framebuffer 0 again.
  void end() const { end(width_, height_, true); }

  // Draws only into the bottom-left region_w x region_h pixels (a cheaper preview while
  // animating), with or without multisampling; no reallocation either way. Show the result
  // with region_uv().
  void begin(int region_w, int region_h, bool multisample) const;
  void end(int region_w, int region_h, bool multisample) const;
  // Texture coordinates of a region's top-left and bottom-right corners (V flipped for UIs).
  void region_uv(int region_w, int region_h, float uv0[2], float uv1[2]) const;

  GLuint texture() const { return texture_.get(); }
  // Sampling of texture(): nearest (the default; exact and cheapest when shown 1:1) or linear
  // (when shown scaled, e.g. a reduced-resolution region while animating).
  void set_linear_filtering(bool linear);
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

  // RGBA8 pixels of the resolved texture, bottom row first (GL order).
  std::vector<std::uint8_t> read_pixels() const;

 private:
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
  bool linear_ = false;
  Framebuffer draw_fbo_;  // multisampled (only when samples_ > 0)
  Renderbuffer colour_ms_;
  Renderbuffer depth_;         // multisampled when samples_ > 0
  Renderbuffer depth_single_;  // for drawing straight into the texture
  Framebuffer resolve_fbo_;    // texture_ + depth_single_ attached
  Texture texture_;
};

}  // namespace render
