// Small OpenGL helpers for the GL voxelizers: compiling and linking a program from GLSL source
// with the driver's log in the error, and turning glGetError into an exception. Need a current
// context (gl/egl_context.h).
#pragma once

#include <string>

namespace dv::gl {

// A linked program of a vertex and a fragment shader; throws dv::Error with the compiler's log.
unsigned link_program(const std::string& vertex_source, const std::string& fragment_source);
// Throws dv::Error("<where>: GL error 0x...") when glGetError reports one.
void check_gl(const char* where);

}  // namespace dv::gl
