// rows.csv writing and reading (rows.h).
#include "experiments/harness/rows.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/number_text.h"
#include "experiments/harness/durable_file.h"

namespace dv {

namespace {

constexpr const char* kHeader =
    "suite,item,experiment,kind,scene,strategy,params,metric,stat,value,unit,note";

std::string quoted(const std::string& field) {
  if (field.find_first_of(",\"\n\r") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Splits one record; `in` supplies continuation lines of quoted fields with line breaks.
std::vector<std::string> split_record(std::string line, std::istream& in, int& line_number) {
  std::vector<std::string> fields(1);
  bool in_quotes = false;
  for (size_t i = 0;; ++i) {
    if (i == line.size()) {
      if (!in_quotes) break;
      std::string next;
      if (!std::getline(in, next)) break;
      ++line_number;
      line += "\n" + next;
    }
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace

std::string rows_csv_header() {
  return std::string(kHeader) + "\n";
}

std::string rows_csv_text(const std::vector<Row>& rows) {
  std::ostringstream out;
  for (const Row& r : rows)
    out << quoted(r.suite) << "," << r.item << "," << quoted(r.experiment) << "," << quoted(r.kind)
        << "," << quoted(r.scene) << "," << quoted(r.strategy) << "," << quoted(r.params) << ","
        << quoted(r.metric) << "," << quoted(r.stat) << "," << exact_text(r.value) << ","
        << quoted(r.unit) << "," << quoted(r.note) << "\n";
  return out.str();
}

void write_rows_csv(const std::string& path, const std::vector<Row>& rows) {
  write_file_atomically(path, rows_csv_header() + rows_csv_text(rows));
}

std::vector<Row> parse_rows_csv(const std::string& text, const std::string& path, int first_line) {
  std::istringstream in(text);
  std::string line;
  std::vector<Row> rows;
  for (int n = first_line; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const int first = n;
    const std::vector<std::string> f = split_record(line, in, n);
    if (f.size() != 12)
      throw InputError(path, "line " + std::to_string(first) + ": expected 12 fields, got " +
                                 std::to_string(f.size()));
    Row r;
    try {
      r.item = std::stoi(f[1]);
      r.value = std::stod(f[9]);
    } catch (const std::exception&) {
      throw InputError(path, "line " + std::to_string(first) + ": item or value is no number");
    }
    r.suite = f[0];
    r.experiment = f[2];
    r.kind = f[3];
    r.scene = f[4];
    r.strategy = f[5];
    r.params = f[6];
    r.metric = f[7];
    r.stat = f[8];
    r.unit = f[10];
    r.note = f[11];
    rows.push_back(std::move(r));
  }
  return rows;
}

size_t rows_csv_body_start(const std::string& text, const std::string& path) {
  const size_t end = std::min(text.find('\n'), text.size());
  std::string first = text.substr(0, end);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first != kHeader)
    throw InputError(path, "line 1: expected the header " + std::string(kHeader));
  return std::min(end + 1, text.size());
}

std::vector<Row> read_rows_csv(const std::string& path) {
  if (!std::ifstream(path)) throw InputError(path, "cannot read rows file");
  const std::string text = read_file_text(path);
  return parse_rows_csv(text.substr(rows_csv_body_start(text, path)), path, 2);
}

void sort_rows_by_item(std::vector<Row>& rows) {
  std::stable_sort(rows.begin(), rows.end(),
                   [](const Row& a, const Row& b) { return a.item < b.item; });
}

Column parse_column(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return {text, ""};
  return {text.substr(0, colon), text.substr(colon + 1)};
}

std::string item_label(const Row& r) {
  return r.strategy + (r.params.empty() ? "" : " " + r.params);
}

bool is_time_metric(const std::string& metric) {
  return metric.size() > 3 && metric.compare(metric.size() - 3, 3, "_ms") == 0;
}

const Row* find_row(const std::vector<const Row*>& rows, const Column& c) {
  for (const std::string& stat :
       c.stat.empty() ? std::vector<std::string>{"value", "median"} : std::vector{c.stat})
    for (const Row* r : rows)
      if (r->metric == c.metric && r->stat == stat) return r;
  return nullptr;
}

}  // namespace dv
