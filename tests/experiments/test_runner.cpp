// The runner end to end on a tiny suite (experiments/scenes/demo.json at 48x32, CPU, about a
// second): every output file, exact answers of the oracle against itself, shards merged equal one
// unsharded run (timings aside), a failed experiment recorded while the suite goes on, and
// Ctrl-C (a real SIGINT through the runner's handler) stopping after the current experiment
// with a report of what was done, and a lossy item marked in the report.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/report.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/runner.h"
#include "experiments/source_paths.h"
#include "tests/experiments/harness_test.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

std::string tiny_suite(const std::string& extra_strategy = "") {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  return R"({"suite": "tiny", "description": "harness test", "repeat": 1, "experiments": [
    {"name": "methods", "kind": "shadow", "scene": ")" +
         scene + R"(",
     "strategy": ["reference", )" +
         extra_strategy + R"({"name": "shadowmap", "params": {"res": 32}},
                  {"name": "dsm", "params": {"res": 32, "eps": 0.05}}],
     "settings": {"width": 48, "height": 32, "probe_points": 40, "seed": 3},
     "plots": [{"type": "bar", "y": "bytes"}]},
    {"name": "storage", "kind": "shadow", "scene": ")" +
         scene + R"(", "strategy": "dsm",
     "params": {"res": 32}, "sweep": {"storage": ["compact", "blocked"]},
     "settings": {"width": 48, "height": 32, "probe_points": 40, "seed": 3, "images": 0}},
    {"name": "voxels", "kind": "voxelize", "scene": ")" +
         scene + R"(",
     "strategy": ["exact", "sat", "slicemap"], "settings": {"res": "32"}}]})";
}

class Runner : public test::HarnessTest {
 protected:
  SuiteOutcome run(const std::string& suite_file, const std::string& shard = "") {
    SuiteOptions o = cpu_options(suite_file);
    o.shard = shard;
    return run_suite(o);
  }
};

double value_of(const std::vector<Row>& rows, int item, const std::string& metric,
                const std::string& stat) {
  for (const Row& r : rows)
    if (r.item == item && r.metric == metric && r.stat == stat) return r.value;
  ADD_FAILURE() << "no row " << item << " " << metric << " " << stat;
  return -1.0;
}

TEST_F(Runner, TinySuiteWritesEveryFileAndTheOracleMatchesItself) {
  const SuiteOutcome r = run(write("tiny.json", tiny_suite()));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.total, 8);
  EXPECT_EQ(r.done, 8);
  EXPECT_EQ(r.failed, 0);
  const fs::path folder(r.folder);
  EXPECT_EQ(folder.parent_path(), dir_ / "out" / "tiny");
  for (const char* file : {"command.txt", "suite.json", "meta.json", "rows.csv", "params.json",
                           "report.md", "images/0_reference.png", "images/1_shadowmap_diff.png"})
    EXPECT_TRUE(fs::exists(folder / file)) << file;
  const std::vector<Row> rows = read_rows_csv((folder / "rows.csv").string());
  // Item 0 is the oracle itself: no error anywhere, and points of both classes were probed.
  EXPECT_EQ(value_of(rows, 0, "probe_error_all", "max"), 0.0);
  EXPECT_EQ(value_of(rows, 0, "image_rmse", "value"), 0.0);
  EXPECT_EQ(value_of(rows, 0, "probe_error_surface", "count"), 20.0);
  EXPECT_EQ(value_of(rows, 0, "probe_error_medium", "count"), 20.0);
  // The camera-visible probes (visible_points defaults to probe_points) and the depth bins: the
  // oracle has no error there either, and the bins' pixels are the image's.
  EXPECT_EQ(value_of(rows, 0, "probe_error_visible", "count"), 40.0);
  EXPECT_EQ(value_of(rows, 0, "probe_error_visible", "max"), 0.0);
  double binned_pixels = 0.0;
  for (const char* bin : {"depth0", "depth1", "depth2", "depth3"}) {
    EXPECT_EQ(value_of(rows, 0, std::string("image_rmse_") + bin, "value"), 0.0) << bin;
    binned_pixels += value_of(rows, 0, std::string("image_pixels_") + bin, "value");
  }
  EXPECT_EQ(binned_pixels, 48.0 * 32.0);
  EXPECT_LE(value_of(rows, 0, "image_depth_edge0", "value"),
            value_of(rows, 0, "image_depth_edge4", "value"));
  EXPECT_GT(value_of(rows, 2, "probe_error_visible", "p50"), -1.0);  // every quantile is written
  EXPECT_GT(value_of(rows, 1, "bytes", "value"), 0.0);               // shadowmap depth maps
  EXPECT_GT(value_of(rows, 2, "probe_error_all", "max"), 0.0);
  EXPECT_EQ(value_of(rows, 2, "generate_ms", "repetitions"), 1.0);
  // The exact voxelizer against exact: nothing missing or extra; sat misses nothing outside the
  // borderline band.
  EXPECT_EQ(value_of(rows, 5, "missing", "value"), 0.0);
  EXPECT_EQ(value_of(rows, 5, "extra", "value"), 0.0);
  EXPECT_EQ(value_of(rows, 6, "missing_outside_band", "value"), 0.0);
  EXPECT_GT(value_of(rows, 6, "filled", "value"), 0.0);
  const Json params = parse_json_file((folder / "params.json").string());
  ASSERT_EQ(params.size(), 8u);
  EXPECT_EQ(params[2]["echoed"]["params"]["res"], 32);
  const Json meta = parse_json_file((folder / "meta.json").string());
  EXPECT_EQ(meta["run"]["backend"], "cpu");
  EXPECT_FALSE(meta["run"]["cpu_model"].get<std::string>().empty());
  EXPECT_TRUE(meta["run"]["machine"].contains("nvidia_driver"));  // "unknown" without a GPU
  EXPECT_TRUE(meta["run"]["machine"].contains("os"));
  EXPECT_EQ(meta["interrupted"], false);
  // Every completion marker says how long its item took, and the items took the run's time.
  std::ifstream progress(folder / "progress.jsonl");
  double item_seconds = 0.0;
  int markers = 0;
  for (std::string line; std::getline(progress, line); ++markers) {
    const Json marker = Json::parse(line);
    ASSERT_TRUE(marker.contains("seconds")) << line;
    EXPECT_GT(marker["seconds"].get<double>(), 0.0) << line;
    item_seconds += marker["seconds"].get<double>();
  }
  EXPECT_EQ(markers, 8);
  EXPECT_LE(item_seconds, meta["elapsed_s"].get<double>());
  std::ifstream report(folder / "report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("## methods (shadow)"), std::string::npos);
  // A CPU run: no line of unknown GPU fields; a GPU it could read is named as not used.
  if (meta["run"]["machine"]["nvidia_driver"] == "unknown") {
    EXPECT_NE(md.find("- GPU: none used (CPU run)\n"), std::string::npos);
    EXPECT_EQ(md.find("NVIDIA driver"), std::string::npos);
  } else {
    EXPECT_NE(md.find("- GPU (present, not used: CPU run): NVIDIA driver "), std::string::npos);
  }
  EXPECT_NE(md.find("- OS: "), std::string::npos);
  EXPECT_NE(md.find("## voxels (voxelize)"), std::string::npos);
  EXPECT_NE(md.find("ran 8 of 8 experiments"), std::string::npos);
  EXPECT_NE(md.find("![](images/0_reference.png)"), std::string::npos);
  EXPECT_NE(md.find("plots"), std::string::npos);
  // `deepvox report` rebuilds the same report from the folder's files.
  fs::remove(folder / "report.md");
  build_report(folder.string());
  std::ifstream rebuilt(folder / "report.md");
  EXPECT_EQ(
      std::string((std::istreambuf_iterator<char>(rebuilt)), std::istreambuf_iterator<char>()), md);
  // A second run makes a new folder.
  EXPECT_NE(run(write("tiny.json", tiny_suite())).folder, r.folder);
}

// A storage past its capacity (a 3D texture of one layer on demo.json's nested media) loses
// nodes: its row is marked lossy in the experiment table with its loss counts listed and in the
// image strip, while the exact storage's row stays unmarked.
TEST_F(Runner, LossyItemIsMarkedWhereverItIsPrinted) {
  const SuiteOutcome r = run(write(
      "tiny.json",
      tiny_suite(
          R"({"name": "dsm", "params": {"res": 32, "storage": "texture3d", "storage.layers": 1}},)")));
  ASSERT_EQ(r.exit_code, 0);
  const fs::path folder(r.folder);
  const std::vector<Row> rows = read_rows_csv((folder / "rows.csv").string());
  ASSERT_GT(value_of(rows, 1, "stats.storage.overflowed_texels", "value"), 0.0)
      << "one layer held every texel: the test needs a scene with more";
  EXPECT_EQ(value_of(rows, 3, "stats.storage.overflowed_texels", "value"), 0.0);  // compact
  std::ifstream report(folder / "report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  const std::string params = "res=32 storage=texture3d storage.layers=1", marked = params + " †";
  EXPECT_NE(md.find("| " + params), std::string::npos) << md;
  EXPECT_NE(md.find(marked + " |"), std::string::npos) << md;  // the table's params cell
  EXPECT_NE(md.find("† lossy: in at least one run a fixed-size structure overflowed"),
            std::string::npos)
      << md;
  const size_t listed = md.find("- item 1 (dsm " + params + "): ");
  ASSERT_NE(listed, std::string::npos) << md;
  const std::string line = md.substr(listed, md.find('\n', listed) - listed);
  EXPECT_NE(line.find("stats.storage.overflowed_texels = " +
                      std::to_string(
                          int64_t(value_of(rows, 1, "stats.storage.overflowed_texels", "value")))),
            std::string::npos)
      << line;
  EXPECT_NE(md.find("dsm " + marked + " |"), std::string::npos) << md;  // image strip
  EXPECT_EQ(md.find("eps=0.05 res=32 †"), std::string::npos) << md;     // the compact dsm
}

TEST_F(Runner, ShardsMergedGiveTheRowsOfOneUnshardedRun) {
  const std::string suite = write("tiny.json", tiny_suite());
  const SuiteOutcome whole = run(suite);
  const SuiteOutcome first = run(suite, "1/2");
  const SuiteOutcome second = run(suite, "2/2");
  EXPECT_EQ(first.done + second.done, whole.done);
  EXPECT_THROW(merge_shards({first.folder}, ""), InputError);  // shard 2 missing
  EXPECT_THROW(merge_shards({first.folder, first.folder}, ""), InputError);
  const std::string merged = merge_shards({second.folder, first.folder}, "");
  const std::vector<std::string> a = test::untimed(read_rows_csv(whole.folder + "/rows.csv"));
  const std::vector<std::string> b = test::untimed(read_rows_csv(merged + "/rows.csv"));
  EXPECT_GT(a.size(), 100u);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(fs::exists(fs::path(merged) / "report.md"));
  EXPECT_TRUE(fs::exists(fs::path(merged) / "images" / "1_shadowmap.png"));
  // A shard of another suite file is refused.
  const SuiteOutcome other = run(write("other.json", tiny_suite() + " "), "2/2");
  EXPECT_THROW(merge_shards({first.folder, other.folder}, ""), InputError);
}

TEST_F(Runner, FailedExperimentIsRecordedAndTheSuiteGoesOn) {
  const SuiteOutcome r =
      run(write("tiny.json",
                tiny_suite(R"("no-such-method", {"name": "shadowmap", "params": {"typo": 1}}, )")));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.failed, 2);
  EXPECT_EQ(r.done, r.total);
  const std::vector<Row> rows = read_rows_csv(r.folder + "/rows.csv");
  EXPECT_EQ(value_of(rows, 1, "failed", "value"), 1.0);
  for (const Row& row : rows) {
    if (row.metric != "failed") continue;
    const std::string expected = row.item == 1 ? "no-such-method" : "typo";
    EXPECT_NE(row.note.find(expected), std::string::npos) << row.note;
  }
  EXPECT_GT(value_of(rows, 4, "bytes", "value"), 0.0);  // the dsm after the failures ran
  std::ifstream report(r.folder + "/report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("failed: shadow method 'no-such-method' not found"), std::string::npos) << md;
}

// An experiment kind registered by the test whose runs cannot run on this backend.
class SkippingDriver : public Driver {
 public:
  std::vector<std::string> settings() const override { return {}; }
  std::vector<std::string> default_columns() const override { return {"ran"}; }
  nlohmann::json run(const RunItem& item, RunContext&, RowSink& rows) override {
    if (item.strategy == "gpu-only") throw SkippedRun("gpu-only does not run on the cpu backend");
    rows.add("ran", "value", 1.0, "count");
    return nlohmann::json::object();
  }
};

TEST_F(Runner, SkippedRunIsRecordedAndIsNoFailure) {
  driver_registry().add("test-skip", "skips gpu-only", {},
                        [](const StrategyParams&) { return std::make_unique<SkippingDriver>(); });
  const SuiteOutcome r = run(write("skip.json", R"({"suite": "skip", "repeat": 1,
    "experiments": [{"name": "e", "kind": "test-skip", "scene": "none.json",
                     "strategy": ["gpu-only", "any"]}]})"));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.skipped, 1);
  EXPECT_EQ(r.failed, 0);
  const std::vector<Row> rows = read_rows_csv(r.folder + "/rows.csv");
  EXPECT_EQ(value_of(rows, 0, "skipped", "value"), 1.0);
  EXPECT_EQ(value_of(rows, 1, "ran", "value"), 1.0);
  std::ifstream report(r.folder + "/report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("| gpu-only | - | skipped |"), std::string::npos) << md;
}

// An experiment kind registered by the test: Ctrl-C arrives while it runs.
class SigintDriver : public Driver {
 public:
  std::vector<std::string> settings() const override { return {}; }
  std::vector<std::string> default_columns() const override { return {"ran"}; }
  nlohmann::json run(const RunItem&, RunContext&, RowSink& rows) override {
    std::raise(SIGINT);  // the runner's handler only sets its flag
    rows.add("ran", "value", 1.0, "count");
    return nlohmann::json::object();
  }
};

TEST_F(Runner, CtrlCWritesFinishedRowsAndAReportOfWhatWasDone) {
  driver_registry().add("test-sigint", "raises SIGINT while it runs", {},
                        [](const StrategyParams&) { return std::make_unique<SigintDriver>(); });
  const SuiteOutcome r = run(write("sigint.json", R"({"suite": "sigint", "repeat": 1,
    "experiments": [{"name": "e", "kind": "test-sigint", "scene": "none.json",
                     "strategy": ["a", "b", "c"]}]})"));
  EXPECT_EQ(r.exit_code, 130);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.done, 1);
  EXPECT_EQ(r.total, 3);
  const std::vector<Row> rows = read_rows_csv(r.folder + "/rows.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].strategy, "a");
  std::ifstream report(r.folder + "/report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("interrupted after 1 of 3 experiments"), std::string::npos) << md;
  // The handler is gone again: the default SIGINT action is back.
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_DFL);
}

}  // namespace
}  // namespace dv
