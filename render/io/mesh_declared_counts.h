// Checks the counts an OFF or PLY file declares against what the file holds, before CGAL's
// readers see it: they size their arrays from the declared counts (a face of 2,000,000,000
// corners, a PLY list of 4,000,000,000 indices) and would allocate and fill gigabytes, or run
// for minutes, on a file of a few bytes. Found by the bad-input corpus.
#pragma once

#include <string>

namespace dv {

// Throws InputError(path, ...) naming the element, the declared count and what the file holds
// when an OFF face or a PLY element or list declares more than the rest of the file can hold;
// and naming the line when a PLY header breaks its grammar (first line 'ply', one 'format
// ascii|binary_little_endian|binary_big_endian 1.0', 'element NAME COUNT', 'property TYPE
// NAME', 'property list TYPE TYPE NAME', comment and obj_info lines, 'end_header'): CGAL's
// reader reads on through other lines and sizes lists from garbage (found by fuzz_mesh).
// Binary OFF is refused (CGAL's reader converts its header without range checks). Other
// formats and well-formed files pass unchanged.
void check_mesh_declared_counts(const std::string& path, const std::string& extension);

}  // namespace dv
