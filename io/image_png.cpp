// PNG output through stb_image_write (header-only, compiled here) and extension dispatch.
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "io/display_encoding.h"
#include "io/image.h"
#include "io/output_path.h"
#include "io/tone_mapping.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FILENAME_CHECK
#include <stb_image_write.h>

namespace dv {

void write_png_bytes(const std::string& path, int width, int height,
                     const std::vector<unsigned char>& rgb) {
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    throw InputError(path, "cannot write PNG file");
}

namespace {

// The bytes of `image` shown through `display`: the encoding's threshold search gives exactly
// srgb_byte of the transformed value without a pow per channel, on the CPU threads.
void write_png_shown(const std::string& path, const Image& image, const DisplayTransform& display) {
  const DisplayEncoding encoding = make_display_encoding(display);
  std::vector<unsigned char> bytes(image.rgb.size());
  cpu_parallel_for_chunks(int64_t(bytes.size()), int64_t(1) << 16, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) bytes[size_t(i)] = encoding.byte(image.rgb[size_t(i)]);
  });
  write_png_bytes(path, image.width, image.height, bytes);
}

}  // namespace

void write_png(const std::string& path, const Image& image) {
  write_png_shown(path, image, DisplayTransform{});
}

void check_image_path(const std::string& path) {
  if (lowercase_extension(path) == ".exr" && !exr_supported())
    write_exr(path, Image());  // throws the reason
  check_output_path(path, {".png", ".exr"}, "image");
}

void write_image(const std::string& path, const Image& image, const DisplayTransform& display) {
  check_image_path(path);
  if (lowercase_extension(path) == ".png") return write_png_shown(path, image, display);
  write_exr(path, image);
}

void write_image(const std::string& path, const Image& image) {
  write_image(path, image, DisplayTransform{});
}

}  // namespace dv
