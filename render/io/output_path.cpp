// check_output_path (see output_path.h).
#include "render/io/output_path.h"

#include <unistd.h>

#include <filesystem>

#include "core/error.h"
#include "core/text.h"

namespace dv {

void check_output_path(const std::string& path, std::initializer_list<const char*> extensions,
                       const std::string& what) {
  namespace fs = std::filesystem;
  const std::string ext = lowercase_extension(path);
  if (extensions.size() > 0) {
    std::string known;
    bool found = false;
    for (const char* e : extensions) {
      known += (known.empty() ? "" : ", ") + std::string(e);
      found = found || ext == e;
    }
    if (!found)
      throw InputError(path, "unknown " + what + " type '" + ext + "' (known: " + known + ")");
  }
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(path, "cannot write the " + what + ": '" + dir.string() +
                               (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));
  if (fs::is_directory(target, ec))
    throw InputError(path, "cannot write the " + what + ": it is a directory");
  if (fs::exists(target, ec) ? ::access(path.c_str(), W_OK) != 0
                             : ::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(path, "cannot write the " + what + ": permission denied");
}

}  // namespace dv
