// An OpenGL 3.3 core context without any window or display: EGL on Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless). Rendering goes into framebuffer objects. Used by the
// `render` command and the renderer tests.
#pragma once

#include <string>

namespace render {

class HeadlessContext {
 public:
  // Creates the context and makes it current on this thread; throws std::runtime_error with
  // the EGL step that failed.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace render
