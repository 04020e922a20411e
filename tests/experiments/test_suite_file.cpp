// Suite files: strict parsing of good and bad files, sweep expansion order, shard slices, the
// rows.csv round trip, timing spreads and result folders that are never overwritten.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_folder.h"
#include "experiments/harness/run_order.h"
#include "experiments/harness/shard_plan.h"
#include "experiments/harness/suite_file.h"
#include "experiments/harness/timing.h"
#include "experiments/source_paths.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

const char* kGood = R"({
  "suite": "good", "description": "two experiments", "repeat": 2,
  "experiments": [
    {"name": "a", "kind": "shadow", "scene": ["s1.json", "s2.json"],
     "strategy": ["none", {"name": "dsm", "params": {"res": 64}}],
     "params": {"bias": 0}, "sweep": {"eps": [0.01, 0.1], "storage": ["compact", "blocked", "chunked"]},
     "settings": {"width": 32, "images": false},
     "paper": {"source": "Knecht 2011", "columns": ["x"], "rows": [[1]]}},
    {"name": "b", "kind": "voxelize", "scene": "s1.json", "strategy": "sat",
     "settings": {"res": "32x32x32"}}
  ]})";

TEST(SuiteFile, ParsesEveryField) {
  const Suite s = parse_suite(kGood, "good.json");
  EXPECT_EQ(s.name, "good");
  EXPECT_EQ(s.repeat, 2);
  ASSERT_EQ(s.experiments.size(), 2u);
  const ExperimentSpec& a = s.experiments[0];
  EXPECT_EQ(a.kind, "shadow");
  EXPECT_EQ(a.scenes, (std::vector<std::string>{"s1.json", "s2.json"}));
  ASSERT_EQ(a.strategies.size(), 2u);
  EXPECT_EQ(a.strategies[1].name, "dsm");
  EXPECT_EQ(a.strategies[1].params.at("res"), "64");
  EXPECT_EQ(a.params.at("bias"), "0");
  EXPECT_EQ(a.settings.at("images"), "0");
  ASSERT_EQ(a.sweep.size(), 2u);
  EXPECT_EQ(a.sweep[0].first, "eps");
  EXPECT_EQ(a.sweep[0].second, (std::vector<std::string>{"0.01", "0.1"}));
  EXPECT_EQ(a.paper["source"], "Knecht 2011");
  EXPECT_EQ(s.hash, fnv1a_hex(kGood));
}

TEST(SuiteFile, SweepIsTheCartesianProductLastKeyFastest) {
  const std::vector<RunItem> items = expand_suite(parse_suite(kGood, "good.json"));
  // a: 2 scenes x 2 strategies x 2 eps x 3 storages = 24; b: 1.
  ASSERT_EQ(items.size(), 25u);
  for (size_t i = 0; i < items.size(); ++i) EXPECT_EQ(items[i].index, int(i));
  EXPECT_EQ(items[0].params_text(), "bias=0 eps=0.01 storage=compact");
  EXPECT_EQ(items[1].params_text(), "bias=0 eps=0.01 storage=blocked");
  EXPECT_EQ(items[3].params_text(), "bias=0 eps=0.1 storage=compact");
  EXPECT_EQ(items[6].strategy, "dsm");
  EXPECT_EQ(items[6].params_text(), "bias=0 eps=0.01 res=64 storage=compact");
  EXPECT_EQ(items[12].scene, "s2.json");
  EXPECT_EQ(items[24].experiment_name, "b");
  EXPECT_EQ(items[24].settings.at("res"), "32x32x32");
  std::set<std::string> distinct;
  for (const RunItem& item : items)
    distinct.insert(item.scene + item.strategy + item.params_text());
  EXPECT_EQ(distinct.size(), items.size());
}

// "aa_duplicates": every item of the experiment again, after its items in the same order, as an
// A/A copy that rows.csv marks "aa=copy" and the strategy never sees.
TEST(SuiteFile, AaDuplicatesCopyEveryItemOfTheExperiment) {
  const std::string text = R"({"suite": "aa", "experiments": [
    {"name": "a", "kind": "shadow", "scene": "s.json", "strategy": "dsm",
     "sweep": {"res": [16, 32]}, "aa_duplicates": true},
    {"name": "b", "kind": "shadow", "scene": "s.json", "strategy": "none"}]})";
  const std::vector<RunItem> items = expand_suite(parse_suite(text, "aa.json"));
  ASSERT_EQ(items.size(), 5u);
  for (size_t i = 0; i < items.size(); ++i) EXPECT_EQ(items[i].index, int(i));
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_FALSE(items[i].aa_copy);
    EXPECT_TRUE(items[i + 2].aa_copy);
    EXPECT_EQ(items[i + 2].params, items[i].params);  // the strategy's parameters are the same
    EXPECT_EQ(items[i + 2].params_text(), items[i].params_text() + " aa=copy");
  }
  EXPECT_EQ(items[2].describe(), "a: dsm res=16 aa=copy on s.json");
  EXPECT_EQ(items[4].experiment_name, "b");
  EXPECT_FALSE(items[4].aa_copy);
  std::string bad = text;
  bad.replace(bad.find("true"), 4, "\"yes\"");
  EXPECT_THROW(parse_suite(bad, "aa.json"), InputError);
}

// The replicate protocol's order: a permutation of the items fixed by the seed, the two sides of
// a comparison claim in adjacent pairs whose orientation alternates (ABBA), the first pair's
// orientation from the seed's lowest bit.
TEST(RunOrder, PermutedBySeedWithClaimSidesInAlternatingPairs) {
  const std::string text = R"({"suite": "order", "experiments": [
    {"name": "a", "kind": "shadow", "scene": "s.json",
     "strategy": ["none", {"name": "dsm", "params": {"res": 32}}],
     "sweep": {"width_hint": [1, 2, 3, 4]},
     "findings": [{"claim": "none faster", "lower": ["strategy=none", "generate_ms"],
                   "than": ["strategy=dsm", "generate_ms"], "timer": "generate_ms"}]},
    {"name": "b", "kind": "shadow", "scene": "s.json", "strategy": "none",
     "sweep": {"x": [1, 2, 3]}}]})";
  const Suite suite = parse_suite(text, "order.json");
  const std::vector<RunItem> items = expand_suite(suite);
  ASSERT_EQ(items.size(), 11u);
  const auto indices = [](const std::vector<RunItem>& v) {
    std::vector<int> out;
    for (const RunItem& item : v) out.push_back(item.index);
    return out;
  };
  for (uint64_t seed : {7ull, 8ull, 12345ull}) {
    const std::vector<RunItem> ordered = protocol_order(items, suite, seed);
    EXPECT_EQ(indices(ordered), indices(protocol_order(items, suite, seed)));  // reproducible
    std::vector<int> sorted = indices(ordered);
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, indices(items));  // a permutation
    // Experiment a's 8 items: 4 adjacent (none, dsm) pairs, orientations alternating.
    int pairs = 0;
    bool none_first = (seed & 1) == 0;
    for (size_t i = 0; i + 1 < ordered.size(); ++i) {
      if (ordered[i].experiment_name != "a") continue;
      ASSERT_EQ(ordered[i + 1].experiment_name, "a") << seed;
      EXPECT_EQ(ordered[i].strategy, none_first ? "none" : "dsm") << seed << " pair " << pairs;
      EXPECT_NE(ordered[i].strategy, ordered[i + 1].strategy) << seed;
      none_first = !none_first;
      ++pairs;
      ++i;
    }
    EXPECT_EQ(pairs, 4) << seed;
  }
  EXPECT_NE(indices(protocol_order(items, suite, 7)), indices(protocol_order(items, suite, 8)));
  EXPECT_NE(indices(protocol_order(items, suite, 7)), indices(items));
}

// A strategy object's `scenes` runs it only on the scenes whose path contains one of the
// parts (the seeds suite gives the 940k-triangle model a larger atlas than the others).
TEST(SuiteFile, StrategyScenesRestrictWhereItRuns) {
  const Suite s = parse_suite(R"({"suite": "x", "experiments": [{"name": "v", "kind": "voxelize",
      "scene": ["m/quad.json", "m/cube.json", "m/buddha.json"],
      "strategy": ["sat", {"name": "atlas", "params": {"atlas": 512}, "scenes": ["quad", "cube"]},
                   {"name": "atlas", "params": {"atlas": 1024}, "scenes": "buddha"}]}]})",
                              "scenes.json");
  std::vector<std::string> runs;
  for (const RunItem& item : expand_suite(s))
    runs.push_back(item.scene + " " + item.strategy + " " + item.params_text());
  EXPECT_EQ(runs,
            (std::vector<std::string>{"m/quad.json sat ", "m/quad.json atlas atlas=512",
                                      "m/cube.json sat ", "m/cube.json atlas atlas=512",
                                      "m/buddha.json sat ", "m/buddha.json atlas atlas=1024"}));
  EXPECT_THROW(parse_suite(R"({"suite": "x", "experiments": [{"name": "v", "kind": "voxelize",
      "scene": "a.json", "strategy": [{"name": "sat", "scenes": [1]}]}]})",
                           "bad.json"),
               InputError);
}

TEST(SuiteFile, BadFilesNameTheFileAndTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "malformed JSON"},
      {"[]", "one JSON object"},
      {R"({"experiments": []})", "suite"},
      {R"({"suite": "x", "experiments": []})", "at least one experiment"},
      {R"({"suite": "x", "typo": 1, "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none"}]})",
       "typo"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "nope", "scene": "s", "strategy": "none"}]})",
       "unknown experiment kind 'nope'"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none", "settings": {"res": 1}}]})",
       "unknown setting 'res'"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none", "sweep": {"eps": []}}]})",
       "non-empty array"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "dsm", "params": {"eps": 1}, "sweep": {"eps": [1]}}]})",
       "also a fixed parameter"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": []}]})",
       "strategy"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none"}, {"name": "a", "kind": "shadow", "scene": "s", "strategy": "none"}]})",
       "used twice"},
      {R"({"suite": "x y", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none"}]})",
       "names a folder"},
      {R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow", "scene": "s", "strategy": "none", "paper": {"rows": 1}}]})",
       "paper"},
  };
  for (const auto& [text, fragment] : cases) {
    try {
      parse_suite(text, "bad-suite.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("bad-suite.json"), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in: " << message;
    }
  }
}

TEST(SuiteFile, BuiltInSuitesLoadAndQuickIsAmongThem) {
  const std::vector<std::string> names = builtin_suite_names();
  for (const char* wanted : {"quick", "seeds", "accuracy", "scale"})
    EXPECT_NE(std::find(names.begin(), names.end(), wanted), names.end()) << wanted;
  for (const std::string& name : names) {
    const Suite s = load_suite(resolve_suite_path(name));
    EXPECT_EQ(s.name, name);
    for (const Suite& form : {s, smoke_suite(s)})
      for (const ExperimentSpec& e : form.experiments) {
        for (const std::string& scene : e.scene_paths) EXPECT_TRUE(fs::exists(scene)) << scene;
        for (const std::string& paper : e.paper_files) EXPECT_TRUE(fs::exists(paper)) << paper;
      }
  }
  // seeds names every paper table file; accuracy has its Pareto fronts.
  std::set<std::string> papers;
  for (const ExperimentSpec& e : load_suite(resolve_suite_path("seeds")).experiments)
    for (const std::string& paper : e.paper_files)
      papers.insert(fs::path(paper).filename().string());
  for (const auto& entry : fs::directory_iterator(test::source_dir() + "/experiments/papers"))
    EXPECT_EQ(papers.count(entry.path().filename().string()), 1u) << entry.path();
  for (const ExperimentSpec& e : load_suite(resolve_suite_path("accuracy")).experiments) {
    if (e.name == "methods") {
      EXPECT_TRUE(e.pareto.is_object());
    }
  }
  // A strategy limited to some scenes names a scene of its experiment (no typo runs nowhere),
  // and the 940,544-triangle Buddha stand-in never gets a 512^2 atlas (262,144 texels: one per
  // triangle does not fit; the committed run of 2026-12-01 had 20 failed rows from it).
  for (const std::string& name : names)
    for (const ExperimentSpec& e : load_suite(resolve_suite_path(name)).experiments)
      for (const StrategySpec& st : e.strategies)
        if (!st.scenes.empty())
          EXPECT_TRUE(std::any_of(e.scenes.begin(), e.scenes.end(),
                                  [&](const std::string& sc) { return st.runs_on(sc); }))
              << name << " " << e.name << " " << st.name;
  int buddha_atlas_items = 0, buddha_atlas_copies = 0;
  for (const RunItem& item : expand_suite(load_suite(resolve_suite_path("seeds"))))
    if (item.strategy.rfind("atlas", 0) == 0 && item.scene.find("buddha") != std::string::npos) {
      ++(item.aa_copy ? buddha_atlas_copies : buddha_atlas_items);
      EXPECT_EQ(item.params.at("atlas"), "1024") << item.experiment_name;
    }
  EXPECT_EQ(buddha_atlas_items, 20);
  EXPECT_EQ(buddha_atlas_copies, 20);  // the voxelize experiments carry A/A controls
  // Every timed experiment of seeds, accuracy and scale runs its A/A controls, in both forms.
  for (const char* name : {"seeds", "accuracy", "scale"}) {
    const Suite s = load_suite(resolve_suite_path(name));
    for (const Suite& form : {s, smoke_suite(s)})
      for (const ExperimentSpec& e : form.experiments)
        EXPECT_TRUE(e.aa_duplicates) << name << " " << e.name;
  }
  EXPECT_THROW(resolve_suite_path("no-such-suite"), InputError);
}

// The scale suite fits each axis from at least six points, its error quantiles rest on at least
// 2,000 camera-visible points, its pixel axis keeps one aspect ratio (so only the pixel density
// grows), its light axes hold one kind of light each and every line plot fits.
TEST(SuiteFile, ScaleSuiteHasSixPointsPerAxis) {
  const Suite s = load_suite(resolve_suite_path("scale"));
  std::set<std::string> names;
  for (const ExperimentSpec& e : s.experiments) {
    names.insert(e.name);
    size_t points = e.scenes.size();
    for (const auto& [key, values] : e.sweep) points *= values.size();
    EXPECT_GE(points, 6u) << e.name;
    EXPECT_GE(std::stoi(e.settings.at("visible_points")), 2000) << e.name;
    for (const auto& plot : e.plots) EXPECT_EQ(plot.value("fit", ""), "power") << e.name;
    std::set<double> aspects;
    std::set<std::string> light_types;
    for (const std::string& path : e.scene_paths) {
      const Json scene = parse_json_file(path);
      aspects.insert(scene["camera"]["width"].get<double>() /
                     scene["camera"]["height"].get<double>());
      for (const Json& light : scene["lights"]) light_types.insert(light["type"]);
    }
    if (e.name == "pixels") {
      EXPECT_EQ(aspects.size(), 1u);
    }
    if (e.name.rfind("lights-", 0) == 0) {
      EXPECT_EQ(light_types, std::set<std::string>{e.name.substr(7)});
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"casters", "pixels", "lights-spot", "lights-omni",
                                          "volume", "dsm-res"}));
}

// Every seeds claim names its timer (the loader checks that its rows carry it); the claims the
// papers timed otherwise than generate_ms are decided on the papers' timers and baselines: Knecht's
// generation on its passes (allocation excluded), Hadwiger's growth with resolution on the march
// pass, Bornik's saving against a texture sized for the deepest texel.
TEST(SuiteFile, SeedsClaimsNameThePapersTimers) {
  const Suite seeds = load_suite(resolve_suite_path("seeds"));
  EXPECT_GT(seeds.practical_bands.count("probe_error_all:mean"), 0u);
  int claims = 0, generation = 0, march = 0, counted = 0;
  for (const ExperimentSpec& e : seeds.experiments)
    for (const auto& f : e.findings) {
      ++claims;
      ASSERT_TRUE(f.contains("timer")) << f["claim"];
      const std::string claim = f["claim"].get<std::string>(), timer = f["timer"];
      if (claim.find("Chunked") == 0 && claim.find("generat") != std::string::npos) {
        EXPECT_EQ(timer, "generate.generation_ms") << claim;
        ++generation;
      }
      if (e.name == "hadwiger" && f.value("over", "") == "res") {
        EXPECT_EQ(timer, "generate.passes.count_ms") << claim;
        ++march;
      }
      if (claim.find("about 80 %") != std::string::npos) {
        EXPECT_NE(f["than"][0].get<std::string>().find("storage.sizing=counted"),
                  std::string::npos);
        ++counted;
      }
    }
  EXPECT_GT(claims, 40);
  EXPECT_EQ(generation, 4);  // dsm-resolution, eps (two), cups
  EXPECT_EQ(march, 1);
  EXPECT_EQ(counted, 1);
}

TEST(SuiteFile, ShardsPartitionTheItemsInOrder) {
  const std::vector<RunItem> items = expand_suite(parse_suite(kGood, "good.json"));
  ItemCosts costs{"estimate", {}};
  for (const RunItem& item : items) costs.by_index[item.index] = estimated_cost(item);
  for (int count : {1, 2, 3, 7, 40}) {
    const ShardPlan plan = plan_shards(items, costs, count);
    std::vector<int> seen;
    for (int i = 1; i <= count; ++i) {
      int previous = -1;
      for (const RunItem& item : shard_items(items, plan, {i, count})) {
        EXPECT_GT(item.index, previous);  // in order within a shard
        previous = item.index;
        seen.push_back(item.index);
      }
    }
    std::sort(seen.begin(), seen.end());
    ASSERT_EQ(seen.size(), items.size()) << count;
    for (size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], int(k));
  }
  EXPECT_EQ(parse_shard("2/3").index, 2);
  for (const char* bad : {"0/2", "3/2", "1", "a/b", "1/0", "1/2x"})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

TEST(SuiteFile, OnlyFiltersByExperimentKindOrStrategy) {
  const std::vector<RunItem> items = expand_suite(parse_suite(kGood, "good.json"));
  EXPECT_EQ(filter_items(items, "voxelize").size(), 1u);
  EXPECT_EQ(filter_items(items, "dsm").size(), 12u);
  EXPECT_EQ(filter_items(items, "").size(), items.size());
}

TEST(Rows, CsvRoundTripKeepsQuotesCommasLineBreaksAndNumbers) {
  const fs::path path = fs::path(test::binary_dir()) / "test_harness_rows.csv";
  const std::vector<Row> rows = {
      {"s", 3, "e,1", "shadow", "a.json", "dsm", "eps=0.05 res=64", "m", "median", 0.1 + 0.2, "ms",
       ""},
      {"s", 4, "e", "shadow", "a.json", "x", "", "failed", "value", 1.0, "",
       "bad \"quote\", comma\nnext line"},
      {"s", 5, "e", "shadow", "a.json", "x", "", "image_psnr", "value", 1.0 / 0.0, "dB", ""}};
  write_rows_csv(path.string(), rows);
  const std::vector<Row> back = read_rows_csv(path.string());
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].experiment, rows[i].experiment);
    EXPECT_EQ(back[i].params, rows[i].params);
    EXPECT_EQ(back[i].note, rows[i].note);
    EXPECT_EQ(back[i].value, rows[i].value);  // bit for bit
    EXPECT_EQ(back[i].item, rows[i].item);
  }
  std::ofstream(path) << "not,the,header\n";
  EXPECT_THROW(read_rows_csv(path.string()), InputError);
}

TEST(Timing, MedianMinMax) {
  const Spread odd = spread_of({5.0, 1.0, 3.0});
  EXPECT_EQ(odd.median, 3.0);
  EXPECT_EQ(odd.min, 1.0);
  EXPECT_EQ(odd.max, 5.0);
  EXPECT_EQ(spread_of({4.0, 1.0, 2.0, 3.0}).median, 2.5);
}

TEST(RunFolder, NeverOverwritesAnExistingFolder) {
  const fs::path out = fs::path(test::binary_dir()) / "test_harness_folders";
  fs::remove_all(out);
  const fs::path a = make_run_folder(out, "quick", "0123456789ab-dirty", "");
  std::ofstream(a / "rows.csv") << "keep me\n";
  const fs::path b = make_run_folder(out, "quick", "0123456789ab-dirty", "");
  const fs::path c = make_run_folder(out, "quick", "0123456789ab-dirty", "");
  EXPECT_NE(a, b);
  EXPECT_NE(b, c);
  EXPECT_NE(a, c);
  EXPECT_EQ(a.parent_path(), out / "quick");
  EXPECT_NE(a.filename().string().find("_0123456-dirty"), std::string::npos) << a;
  std::ifstream kept(a / "rows.csv");
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "keep me");
  EXPECT_EQ(short_git_sha("0123456789ab"), "0123456");
}

}  // namespace
}  // namespace dv
