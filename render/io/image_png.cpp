// PNG output through stb_image_write (header-only, compiled here) and extension dispatch.
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "core/text.h"
#include "render/io/display_encoding.h"
#include "render/io/image.h"
#include "render/io/output_path.h"
#include "render/io/tone_mapping.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FILENAME_CHECK
#include <stb_image_write.h>

namespace dv {

void write_png_bytes(const std::string& path, int width, int height,
                     const std::vector<unsigned char>& rgb) {
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    throw InputError(path, "cannot write PNG file");
}

void write_png(const std::string& path, const Image& image) {
  write_png_bytes(path, image.width, image.height, srgb_bytes(image, DisplayTransform{}));
}

void check_image_path(const std::string& path) {
  if (lowercase_extension(path) == ".exr" && !exr_supported())
    write_exr(path, Image());  // throws the reason
  check_output_path(path, {".png", ".exr"}, "image");
}

void write_image(const std::string& path, const Image& image, const DisplayTransform& display) {
  check_image_path(path);
  if (lowercase_extension(path) == ".png")
    return write_png_bytes(path, image.width, image.height, srgb_bytes(image, display));
  write_exr(path, image);
}

void write_image(const std::string& path, const Image& image) {
  write_image(path, image, DisplayTransform{});
}

}  // namespace dv
