// Move-only RAII owners for OpenGL objects. Every GL name the renderer creates lives in one of
// these, so a cell framebuffer, a mesh or a program is released exactly once, when its owner
// goes away, and only while a context is current (owners must not outlive their context).
#pragma once

#include <epoxy/gl.h>

#include <string>
#include <utility>

namespace render {

template <typename Traits>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0u)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0u);
    }
    return *this;
  }

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }
  static GlHandle create() { return GlHandle(Traits::create()); }

 private:
  GLuint id_ = 0;
};

namespace detail {
struct BufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glGenBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct TextureTraits {
  static GLuint create() {
    GLuint id = 0;
    glGenTextures(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct RenderbufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glGenRenderbuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct ShaderTraits {
  static void destroy(GLuint id) { glDeleteShader(id); }
};
struct ProgramTraits {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
}  // namespace detail

using Buffer = GlHandle<detail::BufferTraits>;
using VertexArray = GlHandle<detail::VertexArrayTraits>;
using Texture = GlHandle<detail::TextureTraits>;
using Renderbuffer = GlHandle<detail::RenderbufferTraits>;
using Framebuffer = GlHandle<detail::FramebufferTraits>;
using Shader = GlHandle<detail::ShaderTraits>;
using Program = GlHandle<detail::ProgramTraits>;

// Compiles one stage; throws std::runtime_error with the driver's log and `label`.
Shader compile_shader(GLenum stage, const std::string& source, const std::string& label);
// Links a vertex + fragment program; throws std::runtime_error with the link log.
Program link_program(const std::string& vertex_source, const std::string& fragment_source,
                     const std::string& label);

// Throws std::runtime_error naming `where` if glGetError reports an error.
void check_gl(const char* where);

}  // namespace render
