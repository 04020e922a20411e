// Deep-shadow-map EXR files in the lean GPU-node build: not available (OpenImageIO is left out
// there on purpose); the error says which build has them.
#include "core/error.h"
#include "render/io/deep_exr.h"

namespace dv {

namespace {

const char* const kNeedsFullBuild =
    "deep EXR files need the full build (this is the lean build without OpenImageIO); "
    "run `deepvox dsm` there, or write only --heatmap here";

}  // namespace

bool deep_exr_supported() {
  return false;
}

void write_deep_exr(const std::string& path, const DeepMapFile&) {
  throw InputError(path, kNeedsFullBuild);
}

DeepMapFile read_deep_exr(const std::string& path) {
  throw InputError(path, kNeedsFullBuild);
}

}  // namespace dv
