// The viewer's image sinks in a headless OpenGL 4.5 context (EGL: Mesa llvmpipe here, the NVIDIA
// driver's EGL device platform on a GPU node): the CPU sink's texture holds exactly the frame's
// bytes, the pixel-buffer upload the CUDA-GL sink ends with fills the texture with exactly the
// buffer's bytes, and on a CUDA build with a GPU the CUDA-GL sink itself (a kernel encoding the
// device image into a buffer registered with cudaGraphicsGLRegisterBuffer) gives the texture
// the bytes the host encoding gives (skipped with the reason elsewhere).
#include <gtest/gtest.h>

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <span>
#include <string>
#include <vector>

#include "apps/viewer/image_sink.h"
#include "cuda/buffer.h"
#include "cuda/device_memory.h"
#include "render/io/display_encoding.h"
#include "tests/gl/gl_test_support.h"

namespace dv::viewer {
namespace {

using ImageSinkGl = test::GlContextTest;

std::vector<unsigned char> pattern(int width, int height) {
  std::vector<unsigned char> bytes(size_t(width) * height * 3);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 37 % 251);
  return bytes;
}

std::vector<unsigned char> texture_bytes(unsigned texture, int width, int height) {
  std::vector<unsigned char> bytes(size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, GL_RGB, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
  return bytes;
}

TEST_F(ImageSinkGl, CpuSinkTextureHoldsTheFrameBytes) {
  auto sink = make_image_sink(Backend::cpu);
  EXPECT_STREQ(sink->last_path(), "texture upload");
  for (const auto& [w, h] : {std::pair{13, 7}, std::pair{8, 8}}) {  // odd rows: no row padding
    const std::vector<unsigned char> bytes = pattern(w, h);
    SinkFrame frame;
    frame.width = w;
    frame.height = h;
    frame.bytes = bytes.data();
    sink->present(frame);
    ASSERT_NE(sink->texture(), 0u);
    EXPECT_EQ(texture_bytes(sink->texture(), w, h), bytes) << w << "x" << h;
  }
}

TEST_F(ImageSinkGl, PixelBufferUploadFillsTheTexture) {
  const int w = 13, h = 7;
  const std::vector<unsigned char> bytes = pattern(w, h);
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferData(buffer, GLsizeiptr(bytes.size()), bytes.data(), GL_STREAM_DRAW);
  ImageTexture texture;
  upload_pixel_buffer(texture, w, h, buffer);
  EXPECT_EQ(texture_bytes(texture.id(), w, h), bytes);
  GLint bound = -1;
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &bound);
  EXPECT_EQ(bound, 0);  // later plain uploads read host memory again
  glDeleteBuffers(1, &buffer);
}

TEST_F(ImageSinkGl, CudaSinkGivesTheHostEncodingsBytes) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "the CUDA-GL sink needs a GPU: " << why;
  const int w = 13, h = 7;
  std::vector<float> linear(size_t(w) * h * 3);
  for (size_t i = 0; i < linear.size(); ++i) linear[i] = float(i % 97) / 80.0f;  // some > 1
  for (const DisplayTransform transform :
       {DisplayTransform{}, DisplayTransform{1.5, ToneCurve::aces}}) {
    const DisplayEncoding encoding = make_display_encoding(transform);
    std::vector<unsigned char> expected(linear.size());
    for (size_t i = 0; i < linear.size(); ++i) expected[i] = encoding.byte(linear[i]);
    const Buffer<float> device(Memory::device, std::span<const float>(linear), "test image");
    auto sink = make_image_sink(Backend::cuda);
    SinkFrame frame;
    frame.width = w;
    frame.height = h;
    frame.bytes = expected.data();
    frame.device_rgb = device.data();
    frame.transform = transform;
    sink->present(frame);
    EXPECT_STREQ(sink->last_path(), "cuda-gl pixel buffer");
    EXPECT_EQ(texture_bytes(sink->texture(), w, h), expected);
  }
}

}  // namespace
}  // namespace dv::viewer
