// The viewer's keys: canonical names (what scripts write and the help overlay lists), their
// aliases, and what each does. One table, read by the script parser, the GLFW key callback and
// the help text, so a key cannot be documented without existing or exist undocumented.
#pragma once

#include <string>
#include <vector>

namespace dv::viewer {

struct KeyInfo {
  const char* name;     // canonical, e.g. "M", "[", "ESCAPE"
  const char* aliases;  // space-separated other names a script may use
  const char* action;
};

const std::vector<KeyInfo>& viewer_keys();
// The canonical name of a key name or alias (case-insensitive), or "" when it is none of them.
std::string key_from_name(const std::string& name);
// Lines "KEY  action" for the help overlay and `deepvox view --help-keys`.
std::string keys_help();

}  // namespace dv::viewer
