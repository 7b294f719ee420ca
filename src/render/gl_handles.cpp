#include "render/gl_handles.hpp"

#include <cstdio>
#include <stdexcept>
#include <vector>

namespace render {

Shader compile_shader(GLenum stage, const std::string& source, const std::string& label) {
  Shader shader(glCreateShader(stage));
  if (!shader) throw std::runtime_error("glCreateShader failed for " + label);
  const char* text = source.c_str();
  glShaderSource(shader.get(), 1, &text, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length > 1 ? length : 1), '\0');
    glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
    throw std::runtime_error("shader " + label + " does not compile: " + log.data());
  }
  return shader;
}

Program link_program(const std::string& vertex_source, const std::string& fragment_source,
                     const std::string& label) {
  const Shader vs = compile_shader(GL_VERTEX_SHADER, vertex_source, label + ".vert");
  const Shader fs = compile_shader(GL_FRAGMENT_SHADER, fragment_source, label + ".frag");
  Program program = Program::create();
  glAttachShader(program.get(), vs.get());
  glAttachShader(program.get(), fs.get());
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length > 1 ? length : 1), '\0');
    glGetProgramInfoLog(program.get(), length, nullptr, log.data());
    throw std::runtime_error("program " + label + " does not link: " + log.data());
  }
  glDetachShader(program.get(), vs.get());
  glDetachShader(program.get(), fs.get());
  return program;
}

void check_gl(const char* where) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char text[32];
    std::snprintf(text, sizeof text, "0x%04X", static_cast<unsigned>(error));
    throw std::runtime_error(std::string("OpenGL error ") + text + " in " + where);
  }
}

}  // namespace render
