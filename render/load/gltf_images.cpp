// The image decoder hook, URI resolution and external image reading (see gltf_images.h).
#include "render/load/gltf_images.h"

#include <cctype>
#include <fstream>
#include <iterator>
#include <optional>
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

// Where the decoded relative path `path` points inside `model_folder`, or why it is refused:
// empty, absolute, or leaving the folder by its '..' steps (see gltf_images.h).
ResolvedUri check_inside_folder(const std::string& path,
                                const std::filesystem::path& model_folder) {
  ResolvedUri out;
  if (path.empty()) {
    out.problem = "empty URI";
    return out;
  }
  if (path.front() == '/' || path.front() == '\\') {
    out.problem = "refused: an absolute path (a model's files must lie in its folder " +
                  model_folder.string() + " or below it)";
    return out;
  }
  const std::filesystem::path relative = std::filesystem::path(path).lexically_normal();
  if (!relative.empty() && *relative.begin() == "..") {
    out.problem = "refused: its '..' steps leave the model's folder " + model_folder.string() +
                  " (a model's files must lie in it or below it)";
    return out;
  }
  out.file = model_folder / relative;
  return out;
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
  return check_inside_folder(path, model_folder);
}

}  // namespace

void install_image_decoder(tinygltf::TinyGLTF& loader, ImageFailures& failures) {
  loader.SetImageLoader(record_undecodable, &failures);
}

namespace {

// tinygltf asks for base_dir joined with the URI it decoded ("base_dir/uri"), then for
// "./uri" (the working directory): the part after "base_dir/", or nullopt for any other path.
std::optional<std::string> uri_part(const BufferFiles& files, const std::string& asked) {
  const std::string prefix = files.base_dir + "/";
  if (asked.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  return asked.substr(prefix.size());
}

// Why the buffer file tinygltf asks for may not be read ("" when it may).
std::string buffer_problem(const BufferFiles& files, const std::string& asked) {
  const std::optional<std::string> uri = uri_part(files, asked);
  if (!uri) return "outside the model's folder";
  const std::string scheme = uri_scheme(*uri);
  if (!scheme.empty())
    return "buffer URI '" + *uri + "': refused: a URI with the scheme '" + scheme +
           ":' (deepvox reads relative references inside the model's folder and data: URIs)";
  const ResolvedUri where = check_inside_folder(*uri, files.base_dir);
  if (!where.problem.empty()) return "buffer URI '" + *uri + "': " + where.problem;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(where.file, ec))
    return where.file.string() + ": buffer file not found (or not a regular file)";
  return "";
}

// A refusal is recorded once (tinygltf asks again for "./uri" when base_dir is ".").
bool buffer_file_exists(const std::string& asked, void* user) {
  BufferFiles& files = *static_cast<BufferFiles*>(user);
  if (!uri_part(files, asked)) return false;
  const std::string problem = buffer_problem(files, asked);
  if (problem.empty()) return true;
  if (files.problems.empty() || files.problems.back() != problem) files.problems.push_back(problem);
  return false;
}

std::string unexpanded(const std::string& path, void*) {
  return path;
}

bool read_buffer_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void* user) {
  const std::string problem = buffer_problem(*static_cast<BufferFiles*>(user), path);
  if (!problem.empty()) {
    if (err) *err = problem;
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "deepvox writes no glTF files";
  return false;
}

}  // namespace

void install_buffer_policy(tinygltf::TinyGLTF& loader, BufferFiles& files) {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = buffer_file_exists;
  callbacks.ExpandFilePath = unexpanded;
  callbacks.ReadWholeFile = read_buffer_file;
  callbacks.WriteWholeFile = write_nothing;
  callbacks.user_data = &files;
  loader.SetFsCallbacks(callbacks);
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
