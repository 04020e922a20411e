// Never-overwriting result folders (run_folder.h).
#include "experiments/harness/run_folder.h"

#include <ctime>

#include "core/error.h"

namespace dv {

namespace fs = std::filesystem;

std::string short_git_sha(const std::string& git_sha) {
  const size_t dash = git_sha.find('-');
  const std::string hex = git_sha.substr(0, std::min<size_t>(dash, 7));
  return dash == std::string::npos ? hex : hex + git_sha.substr(dash);
}

std::string run_folder_name(const std::string& git_sha, const std::string& tag) {
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%d_%H%M%S", std::gmtime(&now));
  return std::string(when) + "_" + short_git_sha(git_sha) + (tag.empty() ? "" : "-" + tag);
}

fs::path make_run_folder(const fs::path& out, const std::string& suite, const std::string& git_sha,
                         const std::string& tag) {
  const fs::path parent = out / suite;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw InputError(parent.string(), "cannot create folder: " + ec.message());
  const std::string base = run_folder_name(git_sha, tag);
  for (int n = 1; n < 10000; ++n) {
    const fs::path dir = parent / (n == 1 ? base : base + "-" + std::to_string(n));
    if (fs::create_directory(dir, ec)) return dir;  // false: it exists already
    if (ec) throw InputError(dir.string(), "cannot create folder: " + ec.message());
  }
  throw InputError(parent.string(), "too many result folders named " + base);
}

}  // namespace dv
