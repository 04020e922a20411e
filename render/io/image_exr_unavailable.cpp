// EXR in the lean GPU-node build: not available (OpenImageIO is left out there on purpose).
#include "core/error.h"
#include "render/io/image.h"

namespace dv {

bool exr_supported() {
  return false;
}

void write_exr(const std::string& path, const Image&) {
  throw InputError(path,
                   "EXR output needs the full build (this is the lean build without OpenImageIO); "
                   "write .png or convert on the host");
}

}  // namespace dv
