// Result folders of suite runs: OUT/<suite>/<YYYY-MM-DD_HHMMSS>_<gitsha7>[-dirty][-TAG], created
// new every time (a folder that exists gets "-2", "-3", ... appended; nothing is overwritten).
#pragma once

#include <filesystem>
#include <string>

namespace dv {

// `git_sha` as build_git_sha() gives it; `tag` e.g. "shard1of2" or "merged" (empty: none).
std::filesystem::path make_run_folder(const std::filesystem::path& out, const std::string& suite,
                                      const std::string& git_sha, const std::string& tag);

// "<YYYY-MM-DD_HHMMSS>_<gitsha7>[-dirty][-TAG]" for now (the name before any "-2" suffix).
std::string run_folder_name(const std::string& git_sha, const std::string& tag);

// "<12 hex>[-dirty]" -> "<7 hex>[-dirty]".
std::string short_git_sha(const std::string& git_sha);

}  // namespace dv
