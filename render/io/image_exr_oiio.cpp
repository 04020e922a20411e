// OpenEXR output through OpenImageIO: linear float RGB, the format for exact comparisons.
#include <OpenImageIO/imageio.h>

#include "core/error.h"
#include "render/io/image.h"

namespace dv {

bool exr_supported() {
  return true;
}

void write_exr(const std::string& path, const Image& image) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError(path, "OpenImageIO cannot create an EXR writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data()) ||
      !out->close())
    throw InputError(path, "cannot write EXR: " + out->geterror());
}

}  // namespace dv
