// Checks the counts an OFF or PLY file declares against what the file holds, before CGAL's
// readers see it: they size their arrays from the declared counts (a face of 2,000,000,000
// corners, a PLY list of 4,000,000,000 indices) and would allocate and fill gigabytes, or run
// for minutes, on a file of a few bytes. Found by the bad-input corpus (issue 14).
#pragma once

#include <string>

namespace dv {

// Throws InputError(path, ...) naming the element, the declared count and what the file holds
// when an OFF face or a PLY element or list declares more than the rest of the file can hold,
// a PLY property comes before any element (CGAL's reader would index an empty list) or the
// header names no known format or a property an unknown type (CGAL's reader reads on and
// sizes lists from garbage; found by fuzz_mesh).
// Other formats, binary OFF and well-formed files pass unchanged.
void check_mesh_declared_counts(const std::string& path, const std::string& extension);

}  // namespace dv
