// The schema of the paper reference tables under experiments/papers/ (docs/paper-tables.md),
// checked with the strict JSON reader: a transcribed table that the suite compares against must
// be well formed before any of its numbers can be trusted. Test-side for now; the suite harness
// can adopt it.
#pragma once

#include <string>
#include <vector>

#include "core/json_reader.h"

namespace dv::test {

struct PaperTable {
  std::string file, source, caption, machine, notes;
  int label_columns = 1;
  std::vector<std::string> columns;
  Json rows;  // array of arrays, each as long as columns
};

// Reads and checks one table; any violation is an InputError naming the file and JSON path.
PaperTable read_paper_table(const Json& document, const std::string& file);
PaperTable load_paper_table(const std::string& path);

// A numeric cell as one number: a plain number, or the midpoint of a [low, high] range. Throws
// InputError for labels and empty (null) cells.
double cell_number(const PaperTable& table, size_t row, size_t column);

}  // namespace dv::test
