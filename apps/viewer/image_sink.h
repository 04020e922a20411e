// How a frame reaches the texture the viewer's window draws. Two sinks behind one interface:
// the CPU one uploads the host bytes (glTextureSubImage2D); the CUDA one (image_sink_cuda.cu,
// compiled only in CUDA builds) encodes the renderer's device image straight into a GL pixel
// buffer registered with cudaGraphicsGLRegisterBuffer and fills the texture from that buffer,
// without a host round trip. Both need a current OpenGL 4.5 context.
#pragma once

#include <memory>

#include "cuda/execute.h"
#include "render/io/tone_mapping.h"

namespace dv::viewer {

struct SinkFrame {
  int width = 0, height = 0;
  // sRGB bytes, 3 a pixel, rows from the top (what the window shows): always given.
  const unsigned char* bytes = nullptr;
  // CUDA: the same picture before encoding, linear rgb in device memory, or null; the CUDA
  // sink encodes it through `transform` (render/io/display_encoding.h) instead of uploading
  // `bytes`.
  const float* device_rgb = nullptr;
  DisplayTransform transform;
};

// An RGB8 texture with nearest sampling, reallocated when the size changes.
class ImageTexture {
 public:
  ImageTexture() = default;
  ~ImageTexture();
  ImageTexture(const ImageTexture&) = delete;
  ImageTexture& operator=(const ImageTexture&) = delete;
  void resize(int width, int height);
  unsigned id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
};

class ImageSink {
 public:
  virtual ~ImageSink() = default;
  // Makes texture() show `frame`.
  virtual void present(const SinkFrame& frame) = 0;
  virtual unsigned texture() const = 0;
  // "texture upload" or "cuda-gl pixel buffer": how the last frame arrived.
  virtual const char* last_path() const = 0;
};

// Host bytes into `texture` (rows from the top; GL's row 0 is the texture's first row).
void upload_bytes(ImageTexture& texture, int width, int height, const unsigned char* bytes);
// The texture from the pixel buffer object `buffer` (width * height * 3 bytes, as upload_bytes).
void upload_pixel_buffer(ImageTexture& texture, int width, int height, unsigned buffer);

// The CPU path: upload_bytes.
std::unique_ptr<ImageSink> make_texture_sink();
// The sink for `backend`: CUDA-GL interop on a CUDA build's cuda backend, else the texture sink.
std::unique_ptr<ImageSink> make_image_sink(Backend backend);

}  // namespace dv::viewer
