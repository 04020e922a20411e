// GLSL compilation and GL error checks (see gl_program.h).
#include "gl/gl_program.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdio>
#include <vector>

#include "core/error.h"

namespace dv::gl {

namespace {

std::string info_log(GLuint object, bool program) {
  GLint length = 0;
  if (program)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(size_t(length > 0 ? length : 1), '\0');
  if (program)
    glGetProgramInfoLog(object, GLsizei(log.size()), nullptr, log.data());
  else
    glGetShaderInfoLog(object, GLsizei(log.size()), nullptr, log.data());
  return log.data();
}

GLuint compile(GLenum kind, const std::string& source) {
  const GLuint shader = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, false);
    glDeleteShader(shader);
    throw Error(std::string(kind == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                " shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

unsigned link_program(const std::string& vertex_source, const std::string& fragment_source) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program, true);
    glDeleteProgram(program);
    throw Error("GL program does not link: " + log);
  }
  return program;
}

void check_gl(const char* where) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
  throw Error(std::string(where) + ": GL error " + code);
}

}  // namespace dv::gl
