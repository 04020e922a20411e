// The tinygltf implementation, compiled once here from Debian's header so no deepvox binary
// links libtinygltf.so. Images are decoded by stb_image, compiled here with private linkage
// (STB_IMAGE_STATIC) so that other users of stb_image (tests) keep their own copy; tinygltf
// decodes embedded images only (TINYGLTF_NO_EXTERNAL_IMAGE): render/load/gltf_images.cpp finds
// and reads external image files itself. deepvox writes no images through tinygltf.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <tiny_gltf.h>
