// The r32ui array image of the GL voxelizers' grids (see gl_grid_image.h).
#include "gl/gl_grid_image.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include "core/error.h"
#include "gl/gl_program.h"

namespace dv::gl {

const char* const kGridImageGlsl = R"(
layout(r32ui, binding = 0) uniform coherent uimage2DArray grid_image;
uniform ivec3 grid_res;
int point_voxel(float g, int res) {
  if (!(g >= 0.0 && g <= float(res))) return -1;
  return min(int(floor(g)), res - 1);
}
void set_voxel(ivec3 v) {
  imageAtomicOr(grid_image, ivec3(v.xy, v.z >> 5), 1u << uint(v.z & 31));
}
)";

int gl_limit(unsigned name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

void require_side(const std::string& where, const std::string& what, int width, int height,
                  int limit) {
  if (width > limit || height > limit)
    throw InputError(where, what + " " + std::to_string(width) + "x" + std::to_string(height) +
                                " exceeds the driver's limit of " + std::to_string(limit) +
                                " texels per side");
}

GridImage::GridImage(const GridSpec& spec, const std::string& where) : spec_(spec) {
  const int layers = spec.words_per_column();
  require_side(where, "grid", spec.res.x, spec.res.y, gl_limit(GL_MAX_TEXTURE_SIZE));
  if (layers > gl_limit(GL_MAX_ARRAY_TEXTURE_LAYERS))
    throw InputError(where, "depth " + std::to_string(spec.res.z) +
                                " needs more array layers than the driver's " +
                                std::to_string(gl_limit(GL_MAX_ARRAY_TEXTURE_LAYERS)));
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
  glTextureStorage3D(texture_, 1, GL_R32UI, spec.res.x, spec.res.y, layers);
  const GLuint zero = 0;
  glClearTexImage(texture_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  check_gl((where + " clear").c_str());
}

GridImage::~GridImage() {
  glDeleteTextures(1, &texture_);
}

void GridImage::bind(unsigned program) const {
  glUniform3i(glGetUniformLocation(program, "grid_res"), spec_.res.x, spec_.res.y, spec_.res.z);
  glBindImageTexture(0, texture_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
}

void GridImage::read_into(VoxelGrid& grid) const {
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  uint32_t* words = grid.view().words;
  const int64_t layer_words = int64_t(spec_.res.x) * spec_.res.y;
  for (int k = 0; k < spec_.words_per_column(); ++k)
    glGetTextureSubImage(texture_, 0, 0, 0, k, spec_.res.x, spec_.res.y, 1, GL_RED_INTEGER,
                         GL_UNSIGNED_INT, GLsizei(layer_words * 4), words + k * layer_words);
  check_gl("grid image readback");
}

}  // namespace dv::gl
