// The image decoder hook, URI resolution and external image reading (see gltf_images.h).
#include "render/load/gltf_images.h"

#include <cctype>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

namespace dv::gltf {
namespace {

// tinygltf's decoder message as a reason: an unknown format said plainly, else its first line.
std::string decode_problem(const std::string& message) {
  if (message.find("Unknown image format") != std::string::npos)
    return "cannot be decoded: not a PNG or JPEG image (or a damaged one)";
  const std::string first = message.substr(0, message.find('\n'));
  return "cannot be decoded: " + (first.empty() ? std::string("unknown reason") : first);
}

// Decodes `size` bytes into image->image (RGBA, 8 or 16 bits); "" or the problem.
std::string decode(tinygltf::Image* image, int index, std::string* warn, int width, int height,
                   const unsigned char* bytes, int size) {
  std::string message;
  if (tinygltf::LoadImageData(image, index, &message, warn, width, height, bytes, size, nullptr))
    return "";
  image->image.clear();
  image->width = image->height = 0;
  return decode_problem(message);
}

bool record_undecodable(tinygltf::Image* image, const int index, std::string*, std::string* warn,
                        int width, int height, const unsigned char* bytes, int size, void* user) {
  const std::string problem = decode(image, index, warn, width, height, bytes, size);
  if (!problem.empty()) (*static_cast<ImageFailures*>(user))[index] = problem;
  return true;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The URI scheme ("http", "file", "C"), or "" for a relative reference (RFC 3986 §3.1: letters,
// digits, '+', '-', '.' from a letter, up to the first ':' before any '/', '?' or '#').
std::string uri_scheme(const std::string& uri) {
  const size_t colon = uri.find(':');
  if (colon == std::string::npos || colon == 0 || uri.find_first_of("/?#") < colon) return "";
  if (!std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
  for (size_t i = 1; i < colon; ++i) {
    const char c = uri[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return "";
  }
  return uri.substr(0, colon);
}

// Where a URI points inside `model_folder`, or why it is refused (see gltf_images.h).
ResolvedUri resolve_reference(const std::string& uri, const std::filesystem::path& model_folder) {
  ResolvedUri out;
  const std::string scheme = uri_scheme(uri);
  if (scheme == "data" || scheme == "DATA") {
    out.problem = "a data: URI that is not a base64 PNG or JPEG image";
    return out;
  }
  if (!scheme.empty()) {
    out.problem = "refused: a URI with the scheme '" + scheme +
                  ":' (deepvox reads relative references inside the model's folder and data: "
                  "URIs)";
    return out;
  }
  const std::string reference = uri.substr(0, uri.find_first_of("?#"));
  std::string path;
  for (size_t i = 0; i < reference.size(); ++i) {
    if (reference[i] != '%') {
      path += reference[i];
      continue;
    }
    const int high = i + 2 < reference.size() ? hex_value(reference[i + 1]) : -1;
    const int low = high >= 0 ? hex_value(reference[i + 2]) : -1;
    if (low < 0 || (high == 0 && low == 0)) {
      out.problem = "malformed percent-encoding at '" + reference.substr(i, 3) + "'";
      return out;
    }
    path += char(high * 16 + low);
    i += 2;
  }
  if (path.empty()) {
    out.problem = "empty URI";
    return out;
  }
  if (path.front() == '/' || path.front() == '\\') {
    out.problem = "refused: an absolute path (images must lie in the model's folder " +
                  model_folder.string() + " or below it)";
    return out;
  }
  const std::filesystem::path relative = std::filesystem::path(path).lexically_normal();
  if (!relative.empty() && *relative.begin() == "..") {
    out.problem = "refused: its '..' steps leave the model's folder " + model_folder.string() +
                  " (images must lie in it or below it)";
    return out;
  }
  out.file = model_folder / relative;
  return out;
}

}  // namespace

void install_image_decoder(tinygltf::TinyGLTF& loader, ImageFailures& failures) {
  loader.SetImageLoader(record_undecodable, &failures);
}

ResolvedUri resolve_image_uri(const std::string& uri, const std::filesystem::path& model_folder) {
  ResolvedUri out = resolve_reference(uri, model_folder);
  if (!out.problem.empty()) out.problem = "URI '" + uri + "': " + out.problem;
  return out;
}

std::string read_external_image(tinygltf::Image& image, int index,
                                const std::filesystem::path& model_folder) {
  const ResolvedUri where = resolve_image_uri(image.uri, model_folder);
  if (!where.problem.empty()) return where.problem;
  const std::string file = where.file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(where.file, ec))
    return file + ": file not found (or not a regular file)";
  std::ifstream in(where.file, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return file + ": read error";
  if (bytes.empty()) return file + ": file is empty";
  if (bytes.size() > size_t(1) << 30) return file + ": larger than 1 GiB";
  std::string warn;
  const std::string problem =
      decode(&image, index, &warn, 0, 0, bytes.data(), static_cast<int>(bytes.size()));
  return problem.empty() ? "" : file + ": " + problem;
}

}  // namespace dv::gltf
