// The viewer's key table (see viewer_keys.h).
#include "apps/viewer/viewer_keys.h"

#include <cctype>
#include <sstream>

namespace dv::viewer {

const std::vector<KeyInfo>& viewer_keys() {
  static const std::vector<KeyInfo> keys = {
      {"M", "", "next shadow method (shadow registry)"},
      {"T", "", "next DSM storage (storage registry)"},
      {"[", "LEFT_BRACKET", "halve eps"},
      {"]", "RIGHT_BRACKET", "double eps"},
      {"-", "MINUS", "halve the DSM / map resolution"},
      {"=", "EQUAL PLUS", "double the DSM / map resolution"},
      {"F", "", "toggle filtering (none / bilinear)"},
      {"C", "", "next cluster count (methods with a `clusters` parameter)"},
      {"V", "", "next voxelizer (voxelizer registry)"},
      {"B", "", "toggle the backend (cpu / cuda)"},
      {"H", "", "toggle the DSM layers-per-texel heat map (dsm)"},
      {"E", "", "toggle the error view (|T - T_oracle| per pixel, with its scale)"},
      {"G", "", "toggle the voxel grid overlay (the method's light grids: slicemap)"},
      {"P", "", "toggle the stats panel"},
      {"S", "", "save image, stats and the `deepvox render` command line"},
      {"R", "", "reset the camera to the scene's"},
      {"F1", "?", "toggle this help"},
      {"Q", "ESCAPE ESC", "quit"},
  };
  return keys;
}

std::string key_from_name(const std::string& name) {
  std::string wanted = name;
  for (char& c : wanted) c = char(std::toupper(static_cast<unsigned char>(c)));
  for (const KeyInfo& k : viewer_keys()) {
    if (wanted == k.name) return k.name;
    std::istringstream aliases(k.aliases);
    for (std::string a; aliases >> a;)
      if (wanted == a) return k.name;
  }
  return "";
}

std::string keys_help() {
  std::string text;
  for (const KeyInfo& k : viewer_keys()) {
    std::string name = k.name;
    name.resize(7, ' ');
    text += name + k.action + "\n";
  }
  return text;
}

}  // namespace dv::viewer
