// The CUDA-GL interop sink (see image_sink.h), compiled only in CUDA builds: a GL pixel buffer
// object registered once with cudaGraphicsGLRegisterBuffer; per frame it is mapped, a kernel
// encodes the renderer's device image into it (render/io/display_encoding.h: the bytes of
// `render`'s PNG), it is unmapped (which orders the kernel before GL's use on the default stream),
// and the texture is filled from it by upload_pixel_buffer. Frames without a device image (coarse
// frames, the error view) take the CPU path's upload.
#include "apps/viewer/image_sink.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <cuda_gl_interop.h>

#include "cuda/cuda_check.h"
#include "cuda/execute.h"
#include "render/io/display_encoding.h"

namespace dv::viewer {

namespace {

class CudaPboSink final : public ImageSink {
 public:
  ~CudaPboSink() override { release(); }

  void present(const SinkFrame& frame) override {
    if (!frame.device_rgb) {
      upload_bytes(texture_, frame.width, frame.height, frame.bytes);
      path_ = "texture upload";
      return;
    }
    ensure_buffer(frame.width, frame.height);
    const DisplayEncoding encoding = make_display_encoding(frame.transform);
    DV_CUDA_CHECK(cudaGraphicsMapResources(1, &resource_, 0));
    void* mapped = nullptr;
    size_t mapped_bytes = 0;
    DV_CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(&mapped, &mapped_bytes, resource_));
    unsigned char* out = static_cast<unsigned char*>(mapped);
    const float* in = frame.device_rgb;
    parallel_for(
        Backend::cuda, "view_encode_display", int64_t(frame.width) * frame.height * 3,
        DV_KERNEL_LAMBDA(int64_t i) { out[i] = encoding.byte(in[i]); });
    DV_CUDA_CHECK(cudaGraphicsUnmapResources(1, &resource_, 0));
    upload_pixel_buffer(texture_, frame.width, frame.height, buffer_);
    path_ = "cuda-gl pixel buffer";
  }
  unsigned texture() const override { return texture_.id(); }
  const char* last_path() const override { return path_; }

 private:
  void ensure_buffer(int width, int height) {
    if (buffer_ && width == width_ && height == height_) return;
    release();
    glCreateBuffers(1, &buffer_);
    glNamedBufferData(buffer_, GLsizeiptr(width) * height * 3, nullptr, GL_STREAM_DRAW);
    DV_CUDA_CHECK(
        cudaGraphicsGLRegisterBuffer(&resource_, buffer_, cudaGraphicsRegisterFlagsWriteDiscard));
    width_ = width;
    height_ = height;
  }
  void release() {
    if (resource_) cudaGraphicsUnregisterResource(resource_);
    if (buffer_) glDeleteBuffers(1, &buffer_);
    resource_ = nullptr;
    buffer_ = 0;
  }

  ImageTexture texture_;
  GLuint buffer_ = 0;
  cudaGraphicsResource_t resource_ = nullptr;
  int width_ = 0, height_ = 0;
  const char* path_ = "texture upload";
};

}  // namespace

std::unique_ptr<ImageSink> make_cuda_pbo_sink() {
  return std::make_unique<CudaPboSink>();
}

}  // namespace dv::viewer
