// The texture, the CPU upload sink and the choice of sink (see image_sink.h).
#include "apps/viewer/image_sink.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include "gl/gl_program.h"

namespace dv::viewer {

#if DEEPVOX_WITH_CUDA
std::unique_ptr<ImageSink> make_cuda_pbo_sink();  // image_sink_cuda.cu
#endif

namespace {

class TextureUploadSink final : public ImageSink {
 public:
  void present(const SinkFrame& frame) override {
    upload_bytes(texture_, frame.width, frame.height, frame.bytes);
  }
  unsigned texture() const override { return texture_.id(); }
  const char* last_path() const override { return "texture upload"; }

 private:
  ImageTexture texture_;
};

}  // namespace

ImageTexture::~ImageTexture() {
  if (id_) glDeleteTextures(1, &id_);
}

void ImageTexture::resize(int width, int height) {
  if (id_ && width == width_ && height == height_) return;
  if (id_) glDeleteTextures(1, &id_);
  glCreateTextures(GL_TEXTURE_2D, 1, &id_);
  glTextureStorage2D(id_, 1, GL_RGB8, width, height);
  glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  width_ = width;
  height_ = height;
}

void upload_bytes(ImageTexture& texture, int width, int height, const unsigned char* bytes) {
  texture.resize(width, height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bytes);
  gl::check_gl("view: texture upload");
}

void upload_pixel_buffer(ImageTexture& texture, int width, int height, unsigned buffer) {
  texture.resize(width, height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
  glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, nullptr);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  gl::check_gl("view: texture from pixel buffer");
}

std::unique_ptr<ImageSink> make_texture_sink() {
  return std::make_unique<TextureUploadSink>();
}

std::unique_ptr<ImageSink> make_image_sink(Backend backend) {
#if DEEPVOX_WITH_CUDA
  if (backend == Backend::cuda) return make_cuda_pbo_sink();
#endif
  (void)backend;
  return make_texture_sink();
}

}  // namespace dv::viewer
