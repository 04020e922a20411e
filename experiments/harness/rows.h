// Measurement rows and rows.csv: tidy, one row per measurement, with the unit in its own column
// (docs/suite-format.md). Columns: suite,item,experiment,kind,scene,strategy,params,metric,stat,
// value,unit,note. `stat` says what the value is (value, median, min, max, ...); `note` carries
// text (an error message, an image path). Fields are quoted as RFC 4180 when needed.
#pragma once

#include <string>
#include <vector>

namespace dv {

struct Row {
  std::string suite;
  int item = 0;
  std::string experiment, kind, scene, strategy, params;
  std::string metric, stat;
  double value = 0.0;
  std::string unit, note;
};

// "dsm res=512 storage=avsm": an item's strategy and its params, as tables label it.
std::string item_label(const Row& r);

// The whole file, written atomically (durable_file.h).
void write_rows_csv(const std::string& path, const std::vector<Row>& rows);
// InputError naming the file and line on a malformed file.
std::vector<Row> read_rows_csv(const std::string& path);

// The header line (with its newline) and the records of `rows`, for appending row groups.
std::string rows_csv_header();
std::string rows_csv_text(const std::vector<Row>& rows);
// Where the records begin in a file's text (after the header line); InputError without it.
size_t rows_csv_body_start(const std::string& text, const std::string& path);
// Records of `text` (no header); errors name `path` and lines counted from `first_line`.
std::vector<Row> parse_rows_csv(const std::string& text, const std::string& path, int first_line);

// A report column "metric" or "metric:stat" (stat empty: "value", else "median").
struct Column {
  std::string metric, stat;
};
Column parse_column(const std::string& text);
// Whether a metric is a time: timers and passes are named "X_ms" (timing.cpp, the stats' "*_ms"
// figures), so "generate_ms" and "generate.passes.count_ms" are, "bytes" is not.
bool is_time_metric(const std::string& metric);
// The row of one item for a column, or nullptr.
const Row* find_row(const std::vector<const Row*>& rows, const Column& c);

// Rows in item order (stable within an item): the order of an unsharded run.
void sort_rows_by_item(std::vector<Row>& rows);

}  // namespace dv
