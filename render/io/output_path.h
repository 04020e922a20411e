// Checking an output file before any work: its extension is one the writer knows, its directory
// exists and is writable, and the path is not a directory or a read-only file. Commands call it
// for every output first, so a typo in a path costs nothing instead of a finished computation.
#pragma once

#include <initializer_list>
#include <string>

namespace dv {

// Throws InputError(path, reason) when `path` cannot be written as `what` (e.g. "stats JSON");
// `extensions` (lower case, with the dot) lists the accepted ones, empty: any.
void check_output_path(const std::string& path, std::initializer_list<const char*> extensions,
                       const std::string& what);

}  // namespace dv
