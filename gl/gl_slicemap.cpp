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
#include "cuda/pass_timer.h"
#include "gl/gl_grid_image.h"
#include "gl/gl_program.h"

namespace dv::gl {

namespace {

// Positions are the grid x, y snapped to 1/256 voxel; each triangle's depth plane in grid
// units (z = a x + b y + c, from the unsnapped corners, in double) goes to the fragments flat,
// so the slice of a fragment is the one its pixel centre's exact depth falls in (interpolating
// a depth varying would use the driver's snapped barycentrics and move points across slice
// planes).
const char* const kVertexShader = R"(#version 450 core
layout(location = 0) in dvec2 grid_xy;
layout(location = 1) in dvec3 plane;
uniform vec2 to_ndc;  // 2 / viewport size (powers of two: exact): window x, y = grid x, y
flat out dvec3 depth_plane;
void main() {
  gl_Position = vec4(float(grid_xy.x) * to_ndc.x - 1.0, float(grid_xy.y) * to_ndc.y - 1.0, 0.0, 1.0);
  depth_plane = plane;
}
)";

// Fragments at grid (x, y) of the window; the slice is the half-open one holding the depth.
const std::string kFragmentShader = std::string("#version 450 core\n") + kGridImageGlsl + R"(
flat in dvec3 depth_plane;
void main() {
  const double depth = depth_plane.x * double(gl_FragCoord.x) +
                       depth_plane.y * double(gl_FragCoord.y) + depth_plane.z;
  if (!(depth >= 0.0lf && depth <= double(grid_res.z)) ||
      any(greaterThanEqual(ivec2(gl_FragCoord.xy), grid_res.xy)))
    discard;
  set_voxel(ivec3(ivec2(gl_FragCoord.xy), min(int(floor(depth)), grid_res.z - 1)));
}
)";

// One vertex as uploaded: snapped grid x, y and its triangle's depth plane (a, b, c).
struct SlicemapVertex {
  double x, y, a, b, c;
};

// The depth plane z = a x + b y + c through three grid points; NaN (no fragment keeps it) for
// triangles seen edge-on.
dvec3 depth_plane(const dvec3& p0, const dvec3& p1, const dvec3& p2) {
  const dvec3 n = glm::cross(p1 - p0, p2 - p0);
  if (n.z == 0.0) return dvec3(0.0, 0.0, std::nan(""));
  return {-n.x / n.z, -n.y / n.z, p0.z + (n.x * p0.x + n.y * p0.y) / n.z};
}

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

int power_of_two_at_least(int n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

// The window is the grid's x, y rounded up to powers of two: they must fit a framebuffer.
void check_framebuffer_limits(const GridSpec& spec) {
  require_side("slicemap (gl)", "grid (rounded up to powers of two)",
               power_of_two_at_least(spec.res.x), power_of_two_at_least(spec.res.y),
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
    std::vector<SlicemapVertex> vertices;
    vertices.reserve(size_t(3 * triangles));
    for (int64_t t = 0; t < triangles; ++t) {
      dvec3 g[3];
      bool finite = true;
      for (int k = 0; k < 3; ++k) {
        g[k] = to_grid.apply(soup.corners[size_t(3 * t + k)]);
        for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(float(g[k][a]));  // GL: floats
      }
      if (!finite) {
        ++skipped;
        continue;
      }
      const dvec3 plane = depth_plane(g[0], g[1], g[2]);
      for (const dvec3& corner : g) {
        // x, y snapped to 1/256 voxel as the shared rasterizer snaps them (round to nearest):
        // exact in float, so the driver's own snapping leaves them alone.
        vertices.push_back({std::floor(corner.x * 256.0 + 0.5) / 256.0,
                            std::floor(corner.y * 256.0 + 0.5) / 256.0, plane.x, plane.y, plane.z});
      }
    }
    glCreateBuffers(1, &gl.buffer);
    // GL rejects empty buffer storage: an empty soup gets one unused vertex's worth.
    if (vertices.empty())
      glNamedBufferStorage(gl.buffer, sizeof(SlicemapVertex), nullptr, 0);
    else
      glNamedBufferStorage(gl.buffer, GLsizeiptr(vertices.size() * sizeof(SlicemapVertex)),
                           vertices.data(), 0);
    glCreateVertexArrays(1, &gl.vertex_array);
    glVertexArrayVertexBuffer(gl.vertex_array, 0, gl.buffer, 0, sizeof(SlicemapVertex));
    glVertexArrayAttribLFormat(gl.vertex_array, 0, 2, GL_DOUBLE, 0);
    glVertexArrayAttribLFormat(gl.vertex_array, 1, 3, GL_DOUBLE, 2 * sizeof(double));
    for (GLuint attribute : {0u, 1u}) {
      glVertexArrayAttribBinding(gl.vertex_array, attribute, 0);
      glEnableVertexArrayAttrib(gl.vertex_array, attribute);
    }
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
    // A power-of-two viewport makes the NDC round trip of the snapped positions exact; the
    // fragments beyond the grid are discarded.
    const int width = power_of_two_at_least(spec.res.x), height = power_of_two_at_least(spec.res.y);
    glNamedFramebufferParameteri(gl.framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(gl.framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_MULTISAMPLE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glUseProgram(gl.program);
    glUniform2f(glGetUniformLocation(gl.program, "to_ndc"), float(2.0 / width),
                float(2.0 / height));
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
