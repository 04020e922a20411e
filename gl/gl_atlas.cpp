// OpenGL atlas voxelization (see gl_atlas.h).
#include "gl/gl_atlas.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "cuda/pass_timer.h"
#include "gl/gl_grid_image.h"
#include "gl/gl_program.h"
#include "strategies/voxelizer/atlas_device.h"
#include "strategies/voxelizer/atlas_packing.h"

namespace dv::gl {

namespace {

constexpr const char* kWhere = "atlas (gl)";
constexpr int kFloatsPerVertex = 10;  // atlas x, y; grid X, Y, Z, W less the base; the base

const char* const kUpdateVertexShader = R"(#version 450 core
layout(location = 0) in vec2 atlas_position;
layout(location = 1) in vec4 grid_offset;  // from the triangle's first corner, interpolated
layout(location = 2) in vec4 grid_base;    // the first corner: small offsets round less
uniform float to_ndc;  // 2 / side: window x, y = atlas x, y
noperspective out vec4 offset;
flat out vec4 base;
void main() {
  gl_Position = vec4(atlas_position * to_ndc - 1.0, 0.0, 1.0);
  offset = grid_offset;
  base = grid_base;
}
)";

const char* const kUpdateFragmentShader = R"(#version 450 core
noperspective in vec4 offset;
flat in vec4 base;
layout(location = 0) out vec4 texel;
void main() { texel = base + offset; }
)";

// One invocation per atlas texel: the texel's point into the grid.
const std::string kPointsVertexShader = std::string("#version 450 core\n") + kGridImageGlsl + R"(
layout(binding = 0) uniform sampler2D positions;
uniform int side;
uniform bool divide;  // frustum grids: x, y are X / W, Y / W
void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 h = texelFetch(positions, ivec2(gl_VertexID % side, gl_VertexID / side), 0);
  if (!(h.w > 0.0)) return;
  vec2 xy = divide ? h.xy / h.w : h.xy;
  ivec3 v = ivec3(point_voxel(xy.x, grid_res.x), point_voxel(xy.y, grid_res.y),
                  point_voxel(h.z, grid_res.z));
  if (v.x >= 0 && v.y >= 0 && v.z >= 0) set_voxel(v);
}
)";

const char* const kNoFragmentShader = R"(#version 450 core
void main() {}
)";

// GL objects of one voxelization, deleted however it ends.
struct AtlasObjects {
  GLuint update_program = 0, points_program = 0, positions = 0, buffer = 0;
  GLuint update_framebuffer = 0, points_framebuffer = 0, vertex_array = 0, empty_array = 0;
  ~AtlasObjects() {
    glDeleteProgram(update_program);
    glDeleteProgram(points_program);
    glDeleteTextures(1, &positions);
    glDeleteBuffers(1, &buffer);
    glDeleteFramebuffers(1, &update_framebuffer);
    glDeleteFramebuffers(1, &points_framebuffer);
    glDeleteVertexArrays(1, &vertex_array);
    glDeleteVertexArrays(1, &empty_array);
  }
};

// The atlas is a render target and a texture; the points are written from vertex shaders.
void check_limits(int side) {
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  const int limit =
      std::min({gl_limit(GL_MAX_TEXTURE_SIZE), gl_limit(GL_MAX_FRAMEBUFFER_WIDTH),
                gl_limit(GL_MAX_FRAMEBUFFER_HEIGHT), int(viewport[0]), int(viewport[1])});
  require_side(kWhere, "atlas", side, side, limit);
  if (gl_limit(GL_MAX_VERTEX_IMAGE_UNIFORMS) < 1)
    throw Error(std::string(kWhere) + ": the driver has no image stores in vertex shaders");
}

// Corner p's homogeneous grid position (gl_atlas.h): affine in p, (X / W, Y / W, Z) is
// to_grid.apply(p) wherever W > 0.
dvec4 homogeneous_grid_position(const GridTransform& to_grid, const dvec3& p) {
  if (!to_grid.frustum) return dvec4(to_grid.apply(p), 1.0);
  const dvec4 clip = to_grid.world_to_clip * dvec4(p, 1.0);
  const double x = clip.x, y = clip.y, w = clip.w;
  return dvec4((0.5 * x + 0.5 * w) * to_grid.scale.x, (0.5 * w - 0.5 * y) * to_grid.scale.y,
               to_grid.depth(p), w);
}

// The vertices of every triangle whose corners are finite in float; returns how many were not.
int64_t atlas_vertices(const TriangleSoup& soup, const AtlasLayout& layout,
                       const GridTransform& to_grid, std::vector<float>& out) {
  const int64_t triangles = soup.triangle_count();
  out.reserve(size_t(3 * kFloatsPerVertex * triangles));
  int64_t skipped = 0;
  for (int64_t t = 0; t < triangles; ++t) {
    float v[3 * kFloatsPerVertex];
    bool finite = true;
    const dvec4 base = homogeneous_grid_position(to_grid, soup.corners[size_t(3 * t)]);
    for (int m = 0; m < 3; ++m) {
      const dvec3 a = atlas_corner_position(layout.cells[size_t(t)], m);
      const dvec4 g = homogeneous_grid_position(to_grid, soup.corners[size_t(3 * t + m)]) - base;
      const double values[kFloatsPerVertex] = {a.x, a.y,    g.x,    g.y,    g.z,
                                               g.w, base.x, base.y, base.z, base.w};
      for (int k = 0; k < kFloatsPerVertex; ++k) {
        v[kFloatsPerVertex * m + k] = float(values[k]);
        finite = finite && std::isfinite(v[kFloatsPerVertex * m + k]);
      }
    }
    if (finite)
      out.insert(out.end(), v, v + 3 * kFloatsPerVertex);
    else
      ++skipped;
  }
  return skipped;
}

void upload(const std::vector<float>& vertices, AtlasObjects& gl) {
  glCreateBuffers(1, &gl.buffer);
  // GL rejects empty buffer storage: no drawable triangle gets one unused vertex's worth.
  const size_t floats = std::max<size_t>(vertices.size(), kFloatsPerVertex);
  glNamedBufferStorage(gl.buffer, GLsizeiptr(floats * sizeof(float)),
                       vertices.empty() ? nullptr : vertices.data(), 0);
  glCreateVertexArrays(1, &gl.vertex_array);
  glVertexArrayVertexBuffer(gl.vertex_array, 0, gl.buffer, 0, kFloatsPerVertex * sizeof(float));
  glVertexArrayAttribFormat(gl.vertex_array, 0, 2, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(gl.vertex_array, 1, 4, GL_FLOAT, GL_FALSE, 2 * sizeof(float));
  glVertexArrayAttribFormat(gl.vertex_array, 2, 4, GL_FLOAT, GL_FALSE, 6 * sizeof(float));
  for (GLuint attribute : {0u, 1u, 2u}) {
    glVertexArrayAttribBinding(gl.vertex_array, attribute, 0);
    glEnableVertexArrayAttrib(gl.vertex_array, attribute);
  }
  glCreateVertexArrays(1, &gl.empty_array);
}

// The position texture as the update pass's render target, and a framebuffer without
// attachments for the points pass (which must not render into the texture it reads).
void make_targets(int side, AtlasObjects& gl) {
  glCreateTextures(GL_TEXTURE_2D, 1, &gl.positions);
  glTextureStorage2D(gl.positions, 1, GL_RGBA32F, side, side);
  glTextureParameteri(gl.positions, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(gl.positions, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateFramebuffers(1, &gl.update_framebuffer);
  glNamedFramebufferTexture(gl.update_framebuffer, GL_COLOR_ATTACHMENT0, gl.positions, 0);
  if (glCheckNamedFramebufferStatus(gl.update_framebuffer, GL_FRAMEBUFFER) !=
      GL_FRAMEBUFFER_COMPLETE)
    throw Error(std::string(kWhere) + ": the RGBA32F position framebuffer is incomplete");
  glCreateFramebuffers(1, &gl.points_framebuffer);
  glNamedFramebufferParameteri(gl.points_framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
  glNamedFramebufferParameteri(gl.points_framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
}

void draw_atlas(int side, GLsizei vertices, const AtlasObjects& gl) {
  const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(gl.update_framebuffer, GL_COLOR, 0, zero);
  glBindFramebuffer(GL_FRAMEBUFFER, gl.update_framebuffer);
  glViewport(0, 0, side, side);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_MULTISAMPLE);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glUseProgram(gl.update_program);
  glUniform1f(glGetUniformLocation(gl.update_program, "to_ndc"), float(2.0 / side));
  glBindVertexArray(gl.vertex_array);
  glDrawArrays(GL_TRIANGLES, 0, vertices);
}

void draw_points(int side, bool frustum, const GridImage& image, const AtlasObjects& gl) {
  glBindFramebuffer(GL_FRAMEBUFFER, gl.points_framebuffer);
  glViewport(0, 0, 1, 1);
  glEnable(GL_RASTERIZER_DISCARD);
  glUseProgram(gl.points_program);
  glUniform1i(glGetUniformLocation(gl.points_program, "side"), side);
  glUniform1i(glGetUniformLocation(gl.points_program, "divide"), frustum ? 1 : 0);
  image.bind(gl.points_program);
  glBindTextureUnit(0, gl.positions);
  glBindVertexArray(gl.empty_array);
  glDrawArrays(GL_POINTS, 0, GLsizei(side * side));
  glDisable(GL_RASTERIZER_DISCARD);
}

}  // namespace

VoxelizeResult voxelize_atlas_gl(const TriangleSoup& soup, const GridSpec& spec, int atlas_side) {
  validate_grid_spec(spec, kWhere);
  check_limits(atlas_side);
  const int64_t triangles = soup.triangle_count();
  VoxelizeResult result;
  AtlasObjects gl;
  PassTimer clear_timer(Backend::cpu);
  result.grid = VoxelGrid(spec, Memory::host);
  const GridImage image(spec, kWhere);
  glFinish();
  result.passes.push_back({"clear", clear_timer.stop()});

  AtlasLayout layout;
  {
    PassTimer timer(Backend::cpu);
    layout = pack_atlas(soup, spec, atlas_side);
    result.passes.push_back({"pack", timer.stop()});
  }
  result.counters["triangles"] = triangles;
  result.counters["atlas_side"] = atlas_side;
  result.counters["texel_size"] = layout.texel_size;
  result.counters["valid_texels"] = layout.valid_texels();
  result.counters["renderer"] = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (triangles == 0) {
    result.counters["skipped_triangles"] = 0;
    return result;
  }

  const GridTransform to_grid = grid_transform(spec);
  std::vector<float> vertices;
  {
    PassTimer timer(Backend::cpu);
    result.counters["skipped_triangles"] = atlas_vertices(soup, layout, to_grid, vertices);
    upload(vertices, gl);
    make_targets(atlas_side, gl);
    glFinish();
    check_gl("atlas (gl) upload");
    result.passes.push_back({"upload", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    gl.update_program = link_program(kUpdateVertexShader, kUpdateFragmentShader);
    gl.points_program = link_program(kPointsVertexShader, kNoFragmentShader);
    result.passes.push_back({"program", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    draw_atlas(atlas_side, GLsizei(vertices.size() / kFloatsPerVertex), gl);
    glFinish();
    check_gl("atlas (gl) atlas_update");
    result.passes.push_back({"atlas_update", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    draw_points(atlas_side, to_grid.frustum, image, gl);
    glFinish();
    check_gl("atlas (gl) points");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    result.passes.push_back({"points", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    image.read_into(result.grid);
    result.passes.push_back({"readback", timer.stop()});
  }
  return result;
}

}  // namespace dv::gl
