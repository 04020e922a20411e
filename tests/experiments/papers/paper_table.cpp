// Schema check of the paper reference tables (see paper_table.h and docs/paper-tables.md).
#include "tests/experiments/papers/paper_table.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace dv::test {
namespace {

bool is_plain_number(const Json& v) {
  return v.is_number() && std::isfinite(v.get<double>());
}

// A value cell: a number, null (the paper leaves it empty or gives no number), or a printed
// range [low, high] with low <= high.
bool is_value_cell(const Json& v) {
  if (v.is_null() || is_plain_number(v)) return true;
  return v.is_array() && v.size() == 2 && is_plain_number(v[0]) && is_plain_number(v[1]) &&
         v[0].get<double>() <= v[1].get<double>();
}

std::string non_empty_string(JsonReader& reader, const std::string& key) {
  std::string value = reader.string(key);
  if (value.find_first_not_of(" \t\n") == std::string::npos) reader.fail(key, "must not be empty");
  return value;
}

std::vector<std::string> string_array(JsonReader& reader, const std::string& key) {
  const Json& value = reader.raw(key);
  if (!value.is_array()) reader.fail(key, "expected an array of strings");
  std::vector<std::string> out;
  for (const Json& item : value) {
    if (!item.is_string()) reader.fail(key, "expected an array of strings");
    out.push_back(item.get<std::string>());
  }
  return out;
}

void check_rows(JsonReader& reader, const PaperTable& table) {
  if (!table.rows.is_array() || table.rows.empty())
    reader.fail("rows", "expected a non-empty array of rows");
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string where = "rows/" + std::to_string(r);
    const Json& row = table.rows[r];
    if (!row.is_array() || row.size() != table.columns.size())
      reader.fail(where,
                  "expected " + std::to_string(table.columns.size()) + " cells, one per column");
    for (size_t c = 0; c < row.size(); ++c) {
      const bool label = int(c) < table.label_columns;
      if (label && !row[c].is_string())
        reader.fail(where + "/" + std::to_string(c), "a label column holds a string");
      if (!label && !is_value_cell(row[c]))
        reader.fail(where + "/" + std::to_string(c),
                    "expected a number, null or a range [low, high], got " + row[c].dump());
    }
  }
}

// Keys of "units": "*" (every value column) or a column name or a row label.
void check_units(JsonReader& reader, const PaperTable& table) {
  const Json& units = reader.raw("units");
  if (!units.is_object() || units.empty()) reader.fail("units", "expected a non-empty object");
  std::vector<std::string> names = table.columns;
  for (const Json& row : table.rows)
    for (int c = 0; c < table.label_columns; ++c) names.push_back(row[c].get<std::string>());
  for (const auto& [key, unit] : units.items()) {
    if (!unit.is_string() || unit.get<std::string>().empty())
      reader.fail("units/" + key, "expected a unit string");
    if (key != "*" && std::find(names.begin(), names.end(), key) == names.end())
      reader.fail("units/" + key, "names no column and no row label");
  }
}

}  // namespace

PaperTable read_paper_table(const Json& document, const std::string& file) {
  JsonReader reader(document, file, "");
  PaperTable table;
  table.file = file;
  table.source = non_empty_string(reader, "source");
  table.caption = non_empty_string(reader, "caption");
  table.machine = non_empty_string(reader, "machine");
  table.notes = non_empty_string(reader, "notes");
  table.columns = string_array(reader, "columns");
  if (table.columns.empty()) reader.fail("columns", "expected at least one column");
  table.label_columns = reader.integer("label_columns", 1);
  if (table.label_columns < 0 || table.label_columns > int(table.columns.size()))
    reader.fail("label_columns", "must lie in [0, number of columns]");
  table.rows = reader.raw("rows");
  check_rows(reader, table);
  check_units(reader, table);
  if (reader.has("quotes")) string_array(reader, "quotes");
  reader.finish();
  return table;
}

PaperTable load_paper_table(const std::string& path) {
  return read_paper_table(parse_json_file(path), path);
}

double cell_number(const PaperTable& table, size_t row, size_t column) {
  const Json& cell = table.rows.at(row).at(column);
  if (is_plain_number(cell)) return cell.get<double>();
  if (cell.is_array()) return 0.5 * (cell[0].get<double>() + cell[1].get<double>());
  throw InputError(table.file + ": /rows/" + std::to_string(row) + "/" + std::to_string(column),
                   "not a numeric cell");
}

}  // namespace dv::test
