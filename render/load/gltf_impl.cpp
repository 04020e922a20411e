// The tinygltf implementation, compiled once here from Debian's header so no deepvox binary
// links libtinygltf.so. Images are never decoded (deepvox reads no textures): no stb_image,
// no external image files; render/load/gltf_import.cpp installs a loader that skips embedded ones.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
