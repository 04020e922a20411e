// A glTF's images as deepvox reads them: embedded ones (data: URIs, .glb buffer views) decoded by
// tinygltf through a decoder that records failures instead of failing the whole file, external
// ones resolved and read here. An image that cannot be used is not an error: the importer warns
// once, naming it and the reason, and the material draws its factor (as viewers do), so one bad
// texture does not refuse a whole model.
//
// External image URIs are relative references (glTF 2.0, "URIs"): a query or fragment is
// dropped, %XX escapes are decoded ('+' stays '+'), and the path is taken relative to the folder
// of the .gltf file. Only files inside that folder (or below it) are read: a URI with a scheme
// (http:, file:, C:), an absolute path (/...) or one whose '..' steps leave the folder is
// refused. A model carries its assets, and a downloaded model must not make the renderer open
// arbitrary files (a '..' chain once opened a system text file as an image). The check is on the
// URI's path, so a symbolic link inside the folder is followed. External buffers (.bin files)
// follow the same policy (install_buffer_policy), and a refused or missing one fails the load
// with an error naming the file: a model without its geometry cannot be drawn.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace dv::gltf {

// Why embedded images (by glTF image index) could not be decoded.
using ImageFailures = std::map<int, std::string>;

// Makes `loader` decode embedded images with stb_image (to RGBA) and record an undecodable one
// in `failures` (its pixels stay empty) instead of failing the load; external images are left
// to read_external_image (tinygltf is built with TINYGLTF_NO_EXTERNAL_IMAGE).
void install_image_decoder(tinygltf::TinyGLTF& loader, ImageFailures& failures);

// The external buffers tinygltf reads while it parses a file from `base_dir` (its folder, "."
// for the working directory), and why any was refused or not found, for the load's error.
struct BufferFiles {
  std::string base_dir;
  std::vector<std::string> problems;
};

// Makes `loader` read external buffers only where the image URI policy above allows, inside
// files.base_dir (never the working directory, which tinygltf tries next, and without its
// expansion of '~' and environment variables), recording why it refused one in `files`.
void install_buffer_policy(tinygltf::TinyGLTF& loader, BufferFiles& files);

// Where an external image URI points inside `model_folder`, or why it is refused (then `file` is
// empty).
struct ResolvedUri {
  std::filesystem::path file;
  std::string problem;
};
ResolvedUri resolve_image_uri(const std::string& uri, const std::filesystem::path& model_folder);

// Reads and decodes image `index` (its uri external) into image.image (RGBA); returns the
// problem ("" on success), naming the file it tried.
std::string read_external_image(tinygltf::Image& image, int index,
                                const std::filesystem::path& model_folder);

}  // namespace dv::gltf
