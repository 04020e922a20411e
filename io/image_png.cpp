// PNG output through stb_image_write (header-only, compiled here) and extension dispatch.
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "core/text.h"
#include "io/image.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FILENAME_CHECK
#include <stb_image_write.h>

namespace dv {

void write_png(const std::string& path, const Image& image) {
  std::vector<unsigned char> bytes(image.rgb.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = srgb_byte(image.rgb[i]);
  if (!stbi_write_png(path.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3))
    throw InputError(path, "cannot write PNG file");
}

void check_image_path(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".exr" && !exr_supported()) write_exr(path, Image());  // throws the reason
  if (ext != ".png" && ext != ".exr")
    throw InputError(path, "unknown image type '" + ext + "' (known: .png, .exr)");
}

void write_image(const std::string& path, const Image& image) {
  check_image_path(path);
  if (lowercase_extension(path) == ".png") return write_png(path, image);
  write_exr(path, image);
}

}  // namespace dv
