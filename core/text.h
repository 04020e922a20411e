// Small text helpers shared by the file loaders, the registries and the CLI: case folding, the
// lower-case extension of a path (file types are chosen by extension, whatever its case), and
// the nearest known word to a mistyped one (edit distance) for "did you mean" hints.
#pragma once

#include <string>
#include <vector>

namespace dv {

std::string lowercase(std::string text);
// ".OBJ" -> ".obj"; empty when the path has no extension.
std::string lowercase_extension(const std::string& path);

// Levenshtein distance: single-character insertions, deletions and substitutions.
int edit_distance(const std::string& a, const std::string& b);
// The candidate nearest to `word` by edit distance (first of equals), or "" when even that one
// differs in more than a third of the word's characters (at least 2): no useful suggestion.
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace dv
