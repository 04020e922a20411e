// The paper reference tables under experiments/papers/: every file passes the schema of
// docs/paper-tables.md through the strict JSON reader, the schema check rejects each kind of
// malformed table, and the numbers that two papers print for the same measurement agree
// (Bornik 2012 reprints Knecht 2011's tables), which catches transcription slips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>

#include "core/error.h"
#include "experiments/source_paths.h"
#include "tests/experiments/papers/paper_table.h"

namespace dv::test {
namespace {

namespace fs = std::filesystem;

std::string papers_dir() {
  return source_dir() + "/experiments/papers";
}

std::vector<std::string> paper_table_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(papers_dir()))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

PaperTable table(const std::string& name) {
  return load_paper_table(papers_dir() + "/" + name);
}

struct FileTestName {
  std::string operator()(const testing::TestParamInfo<std::string>& info) const {
    std::string n = info.param.substr(0, info.param.size() - std::string(".json").size());
    for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    return n;
  }
};

class PaperTableFile : public testing::TestWithParam<std::string> {};

TEST_P(PaperTableFile, PassesTheSchema) {
  try {
    const PaperTable t = table(GetParam());
    EXPECT_FALSE(t.source.empty());
    EXPECT_FALSE(t.machine.empty());
    for (const Json& row : t.rows) EXPECT_EQ(row.size(), t.columns.size());
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Papers, PaperTableFile, testing::ValuesIn(paper_table_files()),
                         FileTestName());

TEST(PaperTables, EveryTableOfTheSeedsListIsThere) {
  std::vector<std::string> expected = {
      "bornik-2012-table-1.json",   "bornik-2012-table-2.json",     "bornik-2012-table-3.json",
      "bornik-2012-table-4.json",   "buchacher-2014-table-1.json",  "buchacher-2014-table-2.json",
      "hadwiger-2006-table-1.json", "knecht-2011-figure-5.13.json", "brabec-2003-figure-5.5.json"};
  for (int k = 1; k <= 11; ++k)
    expected.push_back("knecht-2011-table-5." + std::to_string(k) + ".json");
  const std::vector<std::string> present = paper_table_files();
  for (const std::string& name : expected)
    EXPECT_NE(std::find(present.begin(), present.end(), name), present.end()) << name;
}

// A small valid table, and one mutation per rule: each must be rejected with the JSON path.
Json valid_table() {
  return Json::parse(R"({
    "source": "Paper 2000, Table 1", "caption": "Times.", "machine": "GPU X",
    "units": {"*": "ms", "max": "count"}, "columns": ["[ms]", "a", "max"],
    "rows": [["gen", 1.5, null], ["render", [2, 3], 4]], "notes": "scene.json",
    "quotes": ["as printed"]})");
}

void expect_rejected(const std::function<void(Json&)>& mutate, const std::string& path) {
  Json doc = valid_table();
  mutate(doc);
  try {
    read_paper_table(doc, "t.json");
    ADD_FAILURE() << "accepted a table broken at " << path;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: " + path), std::string::npos) << e.what();
  }
}

TEST(PaperTableSchema, AcceptsTheValidTable) {
  const PaperTable t = read_paper_table(valid_table(), "t.json");
  EXPECT_EQ(t.columns.size(), 3u);
  EXPECT_DOUBLE_EQ(cell_number(t, 0, 1), 1.5);
  EXPECT_DOUBLE_EQ(cell_number(t, 1, 1), 2.5);  // range midpoint
  EXPECT_THROW(cell_number(t, 0, 2), InputError);
  EXPECT_THROW(cell_number(t, 0, 0), InputError);
}

TEST(PaperTableSchema, RejectsEachKindOfMalformedTable) {
  expect_rejected([](Json& d) { d.erase("source"); }, "/source");
  expect_rejected([](Json& d) { d.erase("machine"); }, "/machine");
  expect_rejected([](Json& d) { d["machine"] = " "; }, "/machine");
  expect_rejected([](Json& d) { d["rows"][0].push_back(7); }, "/rows/0");
  expect_rejected([](Json& d) { d["rows"][1].erase(2); }, "/rows/1");
  expect_rejected([](Json& d) { d["rows"][0][1] = "1.5"; }, "/rows/0/1");
  expect_rejected([](Json& d) { d["rows"][0][1] = true; }, "/rows/0/1");
  expect_rejected([](Json& d) { d["rows"][1][1] = Json::array({3, 2}); }, "/rows/1/1");
  expect_rejected([](Json& d) { d["rows"][1][0] = 5; }, "/rows/1/0");
  expect_rejected([](Json& d) { d["rows"] = Json::array(); }, "/rows");
  expect_rejected([](Json& d) { d["units"]["mean"] = "ms"; }, "/units/mean");
  expect_rejected([](Json& d) { d["label_columns"] = 4; }, "/label_columns");
  expect_rejected([](Json& d) { d["extra"] = 1; }, "/");
}

// Bornik 2012 Tables 1 and 3 print "single (clustered)" per cell, one column each here.
void expect_bornik_equals_knecht(const std::string& bornik, const std::string& single,
                                 const std::string& clustered) {
  const PaperTable b = table(bornik), s = table(single), c = table(clustered);
  ASSERT_EQ(b.rows.size(), 3u);
  for (size_t r = 0; r < 3; ++r)
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(cell_number(b, r, 1 + 2 * i), cell_number(s, r, 1 + i)) << bornik << " " << r;
      EXPECT_EQ(cell_number(b, r, 2 + 2 * i), cell_number(c, r, 1 + i)) << bornik << " " << r;
    }
}

TEST(PaperTablesAgree, BornikTable1IsKnecht51And52) {
  expect_bornik_equals_knecht("bornik-2012-table-1.json", "knecht-2011-table-5.1.json",
                              "knecht-2011-table-5.2.json");
}

TEST(PaperTablesAgree, BornikTable3IsKnecht53And54) {
  expect_bornik_equals_knecht("bornik-2012-table-3.json", "knecht-2011-table-5.3.json",
                              "knecht-2011-table-5.4.json");
}

TEST(PaperTablesAgree, BornikTable2IsKnecht56TimesAnd57Layers) {
  const PaperTable b = table("bornik-2012-table-2.json");
  const PaperTable times = table("knecht-2011-table-5.6.json");
  const PaperTable layers = table("knecht-2011-table-5.7.json");
  ASSERT_EQ(b.rows.size(), 6u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(cell_number(b, i, 2), cell_number(times, 0, 1 + i));      // DSM generation
    EXPECT_EQ(cell_number(b, 3 + i, 2), cell_number(times, 1, 1 + i));  // rendering (filt.)
    EXPECT_EQ(cell_number(b, i, 3), cell_number(layers, 0, 1 + i));     // average layers
    EXPECT_EQ(cell_number(b, i, 4), cell_number(layers, 1, 1 + i));     // maximum layers
    EXPECT_EQ(b.rows[i][1], times.columns[1 + i]);
  }
}

TEST(PaperTablesAgree, BornikTable4IsKnecht510) {
  const PaperTable b = table("bornik-2012-table-4.json"), k = table("knecht-2011-table-5.10.json");
  ASSERT_EQ(b.rows.size(), k.rows.size());
  for (size_t r = 0; r < b.rows.size(); ++r)
    for (size_t c = 1; c < b.columns.size(); ++c)
      EXPECT_EQ(cell_number(b, r, c), cell_number(k, r, c));
}

// Buchacher's first sub-table of Table 2 is the grid size W x W x 32; Table 1 and 2 share rows.
TEST(PaperTablesAgree, BuchacherTotalsAreTheGridSizesAndBothTablesShareRows) {
  const PaperTable voxels = table("buchacher-2014-table-2.json");
  const PaperTable times = table("buchacher-2014-table-1.json");
  ASSERT_EQ(voxels.rows[0][0], "Gesamtanzahl Voxel");
  for (size_t c = 2; c < voxels.columns.size(); ++c) {
    const double w = std::stod(voxels.columns[c]);
    EXPECT_EQ(cell_number(voxels, 0, c), w * w * 32);
  }
  ASSERT_EQ(times.rows.size(), voxels.rows.size());
  for (size_t r = 1; r < times.rows.size(); ++r) {
    EXPECT_EQ(times.rows[r][0], voxels.rows[r][0]);
    EXPECT_EQ(times.rows[r][1], voxels.rows[r][1]);
  }
}

}  // namespace
}  // namespace dv::test
