// OpenGL slicemap voxelization (see gl_slicemap.h).
#include "gl/gl_slicemap.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/pass_timer.h"
#include "gl/gl_grid_image.h"
#include "gl/gl_program.h"

namespace dv::gl {

namespace {

const char* const kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 grid_position;
uniform vec2 to_ndc;  // 2 / width, 2 / height: window x, y = grid x, y
noperspective out float grid_depth;
void main() {
  gl_Position = vec4(grid_position.x * to_ndc.x - 1.0, grid_position.y * to_ndc.y - 1.0, 0.0, 1.0);
  grid_depth = grid_position.z;
}
)";

// Fragments at grid (x, y) of the window; the slice is the half-open one holding the depth.
const std::string kFragmentShader = std::string("#version 450 core\n") + kGridImageGlsl + R"(
noperspective in float grid_depth;
void main() {
  int z = point_voxel(grid_depth, grid_res.z);
  if (z < 0) discard;
  set_voxel(ivec3(ivec2(gl_FragCoord.xy), z));
}
)";

// GL objects of one voxelization, deleted however it ends.
struct SlicemapObjects {
  GLuint program = 0, framebuffer = 0, vertex_array = 0, buffer = 0;
  ~SlicemapObjects() {
    glDeleteProgram(program);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteVertexArrays(1, &vertex_array);
    glDeleteBuffers(1, &buffer);
  }
};

// The window is the grid's x, y: they must fit a framebuffer too.
void check_framebuffer_limits(const GridSpec& spec) {
  require_side("slicemap (gl)", "grid", spec.res.x, spec.res.y,
               std::min(gl_limit(GL_MAX_FRAMEBUFFER_WIDTH), gl_limit(GL_MAX_FRAMEBUFFER_HEIGHT)));
}

}  // namespace

VoxelizeResult voxelize_slicemap_gl(const TriangleSoup& soup, const GridSpec& spec) {
  validate_grid_spec(spec, "slicemap (gl)");
  require_affine_grid(spec, "slicemap (gl)");
  check_framebuffer_limits(spec);
  const int64_t triangles = soup.triangle_count();
  if (3 * triangles > INT_MAX)
    throw InputError("slicemap (gl)",
                     std::to_string(triangles) + " triangles exceed one OpenGL draw call");
  VoxelizeResult result;
  SlicemapObjects gl;
  PassTimer clear_timer(Backend::cpu);
  result.grid = VoxelGrid(spec, Memory::host);
  const GridImage image(spec, "slicemap (gl)");
  glFinish();
  result.passes.push_back({"clear", clear_timer.stop()});

  int64_t skipped = 0;
  {
    PassTimer timer(Backend::cpu);
    const GridTransform to_grid = grid_transform(spec);
    std::vector<float> vertices;
    vertices.reserve(size_t(9 * triangles));
    for (int64_t t = 0; t < triangles; ++t) {
      float v[9];
      bool finite = true;
      for (int k = 0; k < 3; ++k) {
        const dvec3 g = to_grid.apply(soup.corners[size_t(3 * t + k)]);
        for (int a = 0; a < 3; ++a) {
          v[3 * k + a] = float(g[a]);
          finite = finite && std::isfinite(v[3 * k + a]);
        }
      }
      if (finite)
        vertices.insert(vertices.end(), v, v + 9);
      else
        ++skipped;
    }
    glCreateBuffers(1, &gl.buffer);
    // GL rejects empty buffer storage: an empty soup gets one unused vertex's worth.
    if (vertices.empty())
      glNamedBufferStorage(gl.buffer, 3 * sizeof(float), nullptr, 0);
    else
      glNamedBufferStorage(gl.buffer, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
                           0);
    glCreateVertexArrays(1, &gl.vertex_array);
    glVertexArrayVertexBuffer(gl.vertex_array, 0, gl.buffer, 0, 3 * sizeof(float));
    glVertexArrayAttribFormat(gl.vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(gl.vertex_array, 0, 0);
    glEnableVertexArrayAttrib(gl.vertex_array, 0);
    glFinish();
    check_gl("slicemap (gl) upload");
    result.passes.push_back({"upload", timer.stop()});
  }
  result.counters["triangles"] = triangles;
  result.counters["skipped_triangles"] = skipped;
  result.counters["renderer"] = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

  {
    PassTimer timer(Backend::cpu);
    gl.program = link_program(kVertexShader, kFragmentShader);
    result.passes.push_back({"program", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    glCreateFramebuffers(1, &gl.framebuffer);
    glNamedFramebufferParameteri(gl.framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, spec.res.x);
    glNamedFramebufferParameteri(gl.framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, spec.res.y);
    glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
    glViewport(0, 0, spec.res.x, spec.res.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_MULTISAMPLE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glUseProgram(gl.program);
    glUniform2f(glGetUniformLocation(gl.program, "to_ndc"), float(2.0 / spec.res.x),
                float(2.0 / spec.res.y));
    image.bind(gl.program);
    glBindVertexArray(gl.vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * (triangles - skipped)));
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glFinish();
    check_gl("slicemap (gl) voxelize");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    result.passes.push_back({"voxelize", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    image.read_into(result.grid);
    result.passes.push_back({"readback", timer.stop()});
  }
  return result;
}

}  // namespace dv::gl
