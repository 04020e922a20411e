// Headless GL works where the tests run: a 4.5 core context through EGL (Mesa llvmpipe here,
// the NVIDIA driver on GPU nodes) clears an integer render target and reads it back, the
// operation the slicemap voxelizer builds on. Skips with the reason where EGL has no display.
#include <gtest/gtest.h>

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <vector>

#include "gl/egl_context.h"

namespace {

TEST(EglContext, ClearsAndReadsBackAnIntegerTarget) {
  std::string why;
  auto ctx = dv::gl::EglContext::create_headless(&why);
  if (!ctx) GTEST_SKIP() << "no headless OpenGL 4.5 here: " << why;
  EXPECT_FALSE(ctx->renderer().empty());
  EXPECT_EQ(ctx->version().rfind("4.", 0), 0u) << ctx->version();
  GLuint tex = 0, fbo = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, 8, 4);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  const GLuint value[4] = {0x80000001u, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, value);
  std::vector<GLuint> pixels(8 * 4, 0);
  glReadPixels(0, 0, 8, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, pixels.data());
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  for (GLuint p : pixels) EXPECT_EQ(p, 0x80000001u);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &tex);
}

}  // namespace
