// Small text helpers shared by the file loaders and the registries: case folding and the
// lower-case extension of a path (file types are chosen by extension, whatever its case).
#pragma once

#include <string>

namespace dv {

std::string lowercase(std::string text);
// ".OBJ" -> ".obj"; empty when the path has no extension.
std::string lowercase_extension(const std::string& path);

}  // namespace dv
