// `deepvox advise`'s library: the search's dominance pruning and its ends, the
// Pareto front, the pick under an error bound and budgets, the exhaustive sweep, shadow config
// files (round trip, refusals), the error model (loading, versioning, prediction) and a small
// CPU advise end to end whose pick's verified error meets the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/advise/advise.h"
#include "experiments/advise/error_model.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/suite_file.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/experiments/harness_test.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

using test::HarnessTest;

// A family over two axes whose cost and error follow the indices: cost 1 + a + 2b, error
// 0.5 / (1 + a + b); the second family costs 100 more at every point (dominated everywhere).
std::vector<AdviseFamily> toy_space() {
  const AdviseAxis a{"a", {"0", "1", "2", "3", "4", "5"}}, b{"b", {"0", "1", "2", "3"}};
  return {{"cheap", "dsm", {{"storage", "compact"}}, {a, b}, {0, 0}},
          {"dear", "dsm", {{"storage", "texture3d"}}, {a, b}, {0, 0}}};
}

AdviseMeasurement toy_measure(const ShadowConfig& c) {
  const int a = std::stoi(c.params.at("a")), b = std::stoi(c.params.at("b"));
  AdviseMeasurement m;
  m.ok = true;
  m.frame_ms = 1.0 + a + 2.0 * b + (c.params.at("storage") == "texture3d" ? 100.0 : 0.0);
  m.error_p95 = m.error_max = 0.5 / (1.0 + a + b);
  m.bytes = 1000.0 * (1 + a);
  return m;
}

AdviseMeasurement point(double error, double ms, double bytes = 0.0) {
  AdviseMeasurement m;
  m.ok = true;
  m.error_p95 = error;
  m.frame_ms = ms;
  m.bytes = bytes;
  return m;
}

TEST(AdviseSearch, DominanceFrontAndPicks) {
  EXPECT_TRUE(dominates(point(0.1, 1.0), point(0.2, 1.0)));
  EXPECT_FALSE(dominates(point(0.1, 2.0), point(0.2, 1.0)));
  EXPECT_FALSE(dominates(point(0.1, 1.0), point(0.1, 1.0)));             // equal: neither
  EXPECT_FALSE(dominates(point(0.1, 1.0, 10.0), point(0.2, 1.0, 5.0)));  // bytes count
  AdviseMeasurement failed = point(0.0, 0.0);
  failed.ok = false;
  EXPECT_FALSE(dominates(failed, point(0.2, 1.0)));

  std::vector<AdviseResult> results;
  for (const AdviseMeasurement& m :
       {point(0.3, 1.0), point(0.1, 3.0), point(0.2, 4.0), point(0.05, 8.0, 50.0), failed})
    results.push_back({{}, {}, m});
  EXPECT_EQ(advise_front(results), (std::vector<size_t>{0, 1, 3}));  // 2 is dominated by 1
  AdviseBudgets budgets;
  budgets.error = 0.2;
  EXPECT_EQ(advise_picks(results, budgets), (std::vector<size_t>{1, 2, 3}));
  budgets.error = 0.06;
  EXPECT_EQ(advise_picks(results, budgets), (std::vector<size_t>{3}));
  budgets.bytes = 40.0;  // the only accurate one is over the memory budget
  EXPECT_TRUE(advise_picks(results, budgets).empty());
  budgets = {};
  budgets.error = 0.2;
  budgets.frame_ms = 3.5;
  EXPECT_EQ(advise_picks(results, budgets), (std::vector<size_t>{1}));
}

// The final timing takes the leading candidates within the band of the cheapest's search time
// (at most `most`) and times them in rounds that rotate their order.
TEST(AdviseSearch, FinalTimingContendersAndInterleavedRounds) {
  std::vector<AdviseResult> results;
  for (double ms : {2.0, 1.0, 1.4, 1.6, 3.0}) results.push_back({{}, {}, point(0.01, ms)});
  AdviseBudgets budgets;
  const std::vector<size_t> picks = advise_picks(results, budgets);
  ASSERT_EQ(picks, (std::vector<size_t>{1, 2, 3, 0, 4}));
  EXPECT_EQ(timing_contenders(results, picks, 1.5, 6), (std::vector<size_t>{1, 2}));
  EXPECT_EQ(timing_contenders(results, picks, 2.0, 6), (std::vector<size_t>{1, 2, 3, 0}));
  EXPECT_EQ(timing_contenders(results, picks, 2.0, 3), (std::vector<size_t>{1, 2, 3}));
  EXPECT_EQ(timing_contenders(results, {4}, 1.5, 6), (std::vector<size_t>{4}));
  EXPECT_TRUE(timing_contenders(results, {}, 1.5, 6).empty());

  const std::vector<std::vector<size_t>> rounds = interleaved_rounds(3, 4);
  ASSERT_EQ(rounds.size(), 4u);
  EXPECT_EQ(rounds[0], (std::vector<size_t>{0, 1, 2}));
  EXPECT_EQ(rounds[1], (std::vector<size_t>{1, 2, 0}));
  EXPECT_EQ(rounds[2], (std::vector<size_t>{2, 0, 1}));
  EXPECT_EQ(rounds[3], (std::vector<size_t>{0, 1, 2}));
  for (size_t place = 0; place < 3; ++place) {  // over the first three rounds each index once
    std::vector<size_t> at;
    for (size_t r = 0; r < 3; ++r) at.push_back(rounds[r][place]);
    std::sort(at.begin(), at.end());
    EXPECT_EQ(at, (std::vector<size_t>{0, 1, 2})) << "place " << place;
  }
}

TEST(AdviseSearch, StopsDominatedBranchesAndFindsTheSweepsCheapest) {
  const std::vector<AdviseFamily> space = toy_space();
  AdviseBudgets budgets;
  budgets.error = 0.1;  // needs a + b >= 4: cheapest a = 4, b = 0 (cost 5)
  AdviseSearchLimits limits;
  const std::vector<AdviseResult> searched = advise_search(space, budgets, toy_measure, limits);
  const std::vector<AdviseResult> swept = advise_sweep(space, toy_measure, limits);
  EXPECT_EQ(swept.size(), 48u);
  EXPECT_LT(searched.size(), swept.size() / 2) << "the search measured most of the space";
  const std::vector<size_t> best_sweep = advise_picks(swept, budgets);
  const std::vector<size_t> best_search = advise_picks(searched, budgets);
  ASSERT_FALSE(best_sweep.empty());
  ASSERT_FALSE(best_search.empty());
  EXPECT_DOUBLE_EQ(searched[best_search[0]].measurement.frame_ms,
                   swept[best_sweep[0]].measurement.frame_ms);
  EXPECT_EQ(searched[best_search[0]].config.param_line(),
            "--shadows dsm --param a=4 --param b=0 --param storage=compact");
  // The dear family is dominated from its start: only its start point is measured.
  int dear = 0;
  for (const AdviseResult& r : searched) dear += r.point.family == 1;
  EXPECT_EQ(dear, 1);
}

TEST(AdviseSearch, LimitsEndTheSearchKeepingWhatWasMeasured) {
  AdviseBudgets budgets;
  budgets.error = 1e-9;  // unreachable: the search would walk on
  AdviseSearchLimits limits;
  limits.max_evaluations = 5;
  EXPECT_EQ(advise_search(toy_space(), budgets, toy_measure, limits).size(), 5u);
  int calls = 0;
  limits.max_evaluations = 100;
  limits.stop = [&] { return calls >= 3; };
  const AdviseMeasure counting = [&](const ShadowConfig& c) {
    ++calls;
    return toy_measure(c);
  };
  EXPECT_EQ(advise_search(toy_space(), budgets, counting, limits).size(), 3u);
}

// A candidate that the fresh points reject carries their worse errors (per stratum, p95, max)
// and a mark; a search continued from the corrected results measures no point twice and walks
// on finer from the rejected point, where it finds the next configuration within the bound.
TEST(AdviseSearch, RejectedAtFreshPointsFoldsInAndTheSearchResumesFiner) {
  AdviseMeasurement searched = point(0.01, 2.0);
  searched.strata[size_t(Stratum::umbra)] = {600, 0.01, 0.2, false, 0.01};
  searched.strata[size_t(Stratum::lit)] = {600, 0.0, 0.0, false, 0.0};
  AdviseMeasurement fresh = point(0.3, 2.1);
  fresh.strata[size_t(Stratum::umbra)] = {600, 0.3, 1.0, false, 0.3};
  fresh.strata[size_t(Stratum::lit)] = {600, 0.0, 0.0, false, 0.0};
  fresh.error_max = 1.0;
  fresh.shadows_measured = false;
  searched.add_fresh_points(fresh);
  EXPECT_TRUE(searched.rejected_at_fresh_points);
  EXPECT_EQ(searched.error_p95, 0.3);
  EXPECT_EQ(searched.error_max, 1.0);
  EXPECT_EQ(searched.strata[size_t(Stratum::umbra)].judged(), 0.3);
  EXPECT_FALSE(searched.shadows_measured);
  EXPECT_EQ(searched.frame_ms, 2.0) << "the search's timing stays";
  AdviseMeasurement failed;
  failed.failure = "a storage limit";
  AdviseMeasurement ok = point(0.0, 1.0);
  ok.add_fresh_points(failed);
  EXPECT_FALSE(ok.ok);

  const std::vector<AdviseFamily> space = {toy_space()[0]};
  AdviseBudgets budgets;
  budgets.error = 0.1;  // a + b >= 4: the search picks a = 4, b = 0
  AdviseSearchLimits limits;
  std::vector<AdviseResult> results = advise_search(space, budgets, toy_measure, limits);
  const std::vector<size_t> picks = advise_picks(results, budgets);
  ASSERT_FALSE(picks.empty());
  ASSERT_EQ(results[picks[0]].point.at, (std::vector<int>{4, 0}));
  // The fresh points see it miss (and every other candidate with it, as on a scene whose
  // search seed was lucky): each is folded in, and the search resumes.
  for (size_t i : picks) results[i].measurement.add_fresh_points(point(0.15, 0.0));
  const size_t before = results.size();
  limits.max_evaluations = int(before) + 8;
  int measured_again = 0;
  const AdviseMeasure counting = [&](const ShadowConfig& c) {
    for (const AdviseResult& r : results) measured_again += r.config.param_line() == c.param_line();
    return toy_measure(c);
  };
  const std::vector<AdviseResult> resumed =
      advise_search(space, budgets, counting, limits, {}, results);
  EXPECT_GT(resumed.size(), before) << "the search did not resume";
  EXPECT_LE(resumed.size(), before + 8);
  EXPECT_EQ(measured_again, 0) << "a point was measured twice";
  const std::vector<size_t> now = advise_picks(resumed, budgets);
  ASSERT_FALSE(now.empty()) << "no new point within the bound";
  EXPECT_FALSE(resumed[now[0]].measurement.rejected_at_fresh_points);
  EXPECT_GE(now[0], before) << "the new pick is one the resumed search measured";
}

TEST(AdviseSearch, SpaceFollowsTheCastersAndItsConfigsAreValid) {
  const std::vector<AdviseFamily> opaque = advise_space({false, false});
  ASSERT_EQ(opaque.size(), 1u);
  EXPECT_EQ(opaque[0].method, "shadowmap");
  for (const AdviseSceneKind kind : {AdviseSceneKind{false, false}, AdviseSceneKind{true, true}})
    for (size_t f = 0; const AdviseFamily& family : advise_space(kind)) {
      ASSERT_EQ(family.start.size(), family.axes.size()) << family.name;
      // Every value of every axis builds (the registry checks names and ranges).
      for (size_t a = 0; a < family.axes.size(); ++a)
        for (size_t v = 0; v < family.axes[a].values.size(); ++v) {
          AdvisePoint p{int(f), family.start};
          p.at[a] = int(v);
          const ShadowConfig c = config_at(advise_space(kind), p);
          EXPECT_NO_THROW(shadow_registry().create(c.name, StrategyParams(c.params)))
              << c.param_line();
        }
      ++f;
    }
}

class AdviseFiles : public HarnessTest {};

TEST_F(AdviseFiles, ShadowConfigRoundTripAndRefusals) {
  const ShadowConfig c{
      "dsm", {{"storage", "avsm"}, {"res", "256"}, {"eps", "0.01"}, {"storage.nodes", "8"}}};
  const std::string path = (dir_ / "pick.json").string();
  write_shadow_config(path, c, {{"advice", {{"scene", "s.json"}}}});
  const ShadowConfig back = read_shadow_config(path);
  EXPECT_EQ(back.name, c.name);
  EXPECT_EQ(back.params, c.params);
  const nlohmann::json j = parse_json_file(path);
  EXPECT_EQ(j["shadows"]["params"]["res"], 256);  // numbers stay numbers
  EXPECT_EQ(j["shadows"]["params"]["eps"], 0.01);
  EXPECT_EQ(j["shadows"]["params"]["storage"], "avsm");  // and names names
  EXPECT_EQ(j["advice"]["scene"], "s.json");
  EXPECT_EQ(c.param_line(),
            "--shadows dsm --param eps=0.01 --param res=256 --param storage=avsm "
            "--param storage.nodes=8");
  const auto refused = [&](const std::string& text, const std::string& fragment) {
    const std::string bad = write("bad.json", text);
    try {
      read_shadow_config(bad);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  };
  refused(R"({"shadows": {"name": "dsm"}})", "format");
  refused(R"({"format": "deepvox-shadow-config", "version": 2, "shadows": {"name": "dsm"}})",
          "version 2");
  refused(R"({"format": "deepvox-shadow-config", "version": 1, "shadows": {"name": "nope"}})",
          "nope");
  refused(R"({"format": "deepvox-shadow-config", "version": 1,
              "shadows": {"name": "dsm", "params": {"res": 0}}})",
          "res");
}

// A suite file names a shadow config as a strategy.
TEST_F(AdviseFiles, SuiteFilesNameAConfig) {
  write_shadow_config((dir_ / "pick.json").string(), {"dsm", {{"storage", "beer"}, {"res", "64"}}});
  const std::string suite = write("s.json", R"({"suite": "s", "experiments": [{"name": "e",
    "kind": "shadow", "scene": "scene.json", "strategy": [{"config": "pick.json"}]}]})");
  const std::vector<RunItem> items = expand_suite(load_suite(suite));
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].strategy, "dsm");
  EXPECT_EQ(items[0].params.at("storage"), "beer");
  EXPECT_EQ(items[0].params.at("res"), "64");
}

TEST_F(AdviseFiles, ErrorModelLoadsVersionedAndPredicts) {
  ErrorModel model;
  model.source = {{"run", "test"}};
  LightStats media;
  media.kind = LightKind::media;
  media.casters = 2;
  media.volumes = 1;
  media.smallest_caster = 0.2;
  CalibrationScene scene{"a.json", {media}, {}};
  const auto config = [](const std::string& res, double p95, double ms) {
    return CalibratedConfig{{"auto", {{"storage", "compact"}, {"res", res}}}, p95, ms, 1e6};
  };
  scene.configs = {config("128", 0.05, 1.0), config("256", 0.01, 2.0), config("512", 0.002, 4.0)};
  model.scenes.push_back(scene);
  const std::string path = (dir_ / "model.json").string();
  write_error_model(path, model);
  const ErrorModel back = read_error_model(path);
  ASSERT_EQ(back.scenes.size(), 1u);
  EXPECT_EQ(back.scenes[0].configs.size(), 3u);
  EXPECT_EQ(back.scenes[0].lights[0].kind, LightKind::media);

  // margin 1.25: 0.01 x 1.25 = 0.0125 fits 0.02; 0.05 x 1.25 does not.
  BudgetPrediction p = predict_budget(back, {media}, 0.02);
  ASSERT_TRUE(p.confident) << p.why;
  EXPECT_EQ(p.pick.params.at("res"), "256");
  EXPECT_NEAR(p.lights[0].predicted, 0.0125, 1e-12);
  EXPECT_EQ(predict_budget(back, {media}, 0.001).confident, false);  // nothing calibrated fits
  LightStats fine = media;
  fine.smallest_caster = 0.05;  // finer than half the calibrated 0.2: measure instead
  EXPECT_FALSE(predict_budget(back, {fine}, 0.02).confident);
  LightStats opaque;
  opaque.kind = LightKind::opaque;
  opaque.casters = opaque.opaque = 1;
  opaque.smallest_caster = 0.3;
  const BudgetPrediction unknown = predict_budget(back, {opaque}, 0.02);
  EXPECT_FALSE(unknown.confident);
  EXPECT_NE(unknown.lights[0].why.find("opaque"), std::string::npos) << unknown.lights[0].why;

  nlohmann::json newer = back.to_json();
  newer["version"] = kErrorModelVersion + 1;
  std::ofstream(dir_ / "newer.json") << newer.dump();
  EXPECT_THROW(read_error_model((dir_ / "newer.json").string()), InputError);
}

// The committed model reads and holds the accuracy suite's four scenes.
TEST(ErrorModel, CommittedModelLoads) {
  const ErrorModel model = read_error_model(default_error_model_path());
  EXPECT_EQ(model.version, kErrorModelVersion);
  EXPECT_EQ(model.scenes.size(), 4u);
  for (const CalibrationScene& s : model.scenes) EXPECT_GT(s.configs.size(), 20u) << s.scene;
}

// A small scene on the CPU (the floor's edges outside the view, as test_cli's advise scene
// says why): the pick's error at fresh points meets the bound.
TEST_F(AdviseFiles, SmallCpuAdviceMeetsItsBoundAtFreshPoints) {
  const std::string scene = write("scene.json", R"({
  "camera": {"position": [0, 1, 4], "target": [0, 0.3, 0], "width": 48, "height": 36},
  "lights": [{"type": "omni", "position": [0.5, 3, 0.5], "intensity": 9}],
  "objects": [
    {"mesh": {"generator": "box", "min": [-6, -0.1, -6], "max": [6, 0, 6]}},
    {"name": "glass", "mesh": {"generator": "box", "size": 0.6}, "transform": {"translate": [0, 0.6, 0]},
     "material": {"alpha": 0.4}, "interior": {"type": "constant", "sigma": 1.5}}
  ]})");
  SceneCache cache(Backend::cpu);
  AdviseOptions o;
  o.scene = scene;
  o.budgets.error = 0.05;
  o.settings.width = 32;
  o.settings.probes = 100;
  o.settings.repeat = 1;
  o.max_evaluations = 6;
  o.max_res = 256;
  const Advice advice = advise(cache, o);
  ASSERT_TRUE(advice.pick.has_value()) << "no pick among " << advice.results.size();
  EXPECT_LE(advice.verified.error_p95, o.budgets.error);
  EXPECT_LE(advice.results[*advice.pick].measurement.error_p95, o.budgets.error);
  EXPECT_NE(advice.verify_seed, o.settings.seed);
  EXPECT_LE(int(advice.results.size()), o.max_evaluations);
  EXPECT_FALSE(advice.front.empty());
  // The final timing: every contender timed once per round; the pick's time is its median.
  for (const Advice::FinalTiming& t : advice.final_timing) {
    EXPECT_EQ(int(t.times_ms.size()), o.final_rounds);
    EXPECT_LT(t.index, advice.results.size());
    if (t.index == *advice.pick) {
      EXPECT_EQ(advice.chosen_ms(t.index), t.median_ms);
    }
  }
}

// A replicate protocol's rounds: the model takes each configuration's error and bytes from the
// folder, its frame time as the median over the folder and the runs its runs.json names, and
// leaves out the A/A copies (the same configuration measured again, params "aa=copy").
TEST(ErrorModel, CalibrationPoolsTheRecordedRunsAndLeavesOutAaCopies) {
  const std::filesystem::path root = test::scratch_dir("test_advise_tmp");
  const std::string scene = test::source_dir() + "/experiments/scenes/knecht-quick.json";
  const auto rows_of = [&](double coarse_ms, double copy_ms) {
    std::vector<Row> rows;
    const auto add = [&](int item, const std::string& params, const std::string& metric,
                         const std::string& stat, double value) {
      Row r;
      r.suite = "accuracy", r.item = item, r.experiment = "methods", r.kind = "shadow";
      r.scene = scene, r.strategy = "dsm", r.params = params;
      r.metric = metric, r.stat = stat, r.value = value;
      rows.push_back(r);
    };
    const std::string coarse = "eps=0.05 res=256 storage=compact";
    const std::string fine = "eps=0.05 res=512 storage=compact";
    for (const auto& [item, params, ms, p95] :
         {std::tuple{0, coarse, coarse_ms, 0.04}, std::tuple{1, fine, 5.0, 0.01},
          std::tuple{2, coarse + " aa=copy", copy_ms, 0.04}}) {
      add(item, params, "strata_error", "judged", p95);
      add(item, params, "frame_ms", "value", ms);
      add(item, params, "bytes", "value", 1000.0 * (item + 1));
    }
    return rows;
  };
  const double coarse_ms[] = {2.0, 4.0, 3.0};
  for (int run = 0; run < 3; ++run) {
    const std::filesystem::path dir = root / ("run" + std::to_string(run));
    std::filesystem::create_directories(dir);
    write_rows_csv((dir / "rows.csv").string(), rows_of(coarse_ms[run], 40.0));
    std::ofstream(dir / "meta.json") << R"({"suite": "accuracy", "suite_hash": "h", "done": 3})";
  }
  std::ofstream(root / "run0" / "runs.json") << R"({"runs": ["../run1", "../run2"]})";
  const ErrorModel model = calibrate_error_model((root / "run0").string());
  EXPECT_EQ(model.source["runs"], 3);
  ASSERT_EQ(model.scenes.size(), 1u);
  ASSERT_EQ(model.scenes[0].configs.size(), 2u) << "the A/A copy is no configuration";
  for (const CalibratedConfig& c : model.scenes[0].configs) {
    EXPECT_EQ(c.shadows.params.count("aa"), 0u);
    const bool coarse = c.shadows.params.at("res") == "256";
    EXPECT_DOUBLE_EQ(c.frame_ms, coarse ? 3.0 : 5.0) << "the median over the three runs";
    EXPECT_DOUBLE_EQ(c.p95, coarse ? 0.04 : 0.01);
    EXPECT_DOUBLE_EQ(c.bytes, coarse ? 1000.0 : 2000.0);
  }
  std::ofstream(root / "run2" / "meta.json")
      << R"({"suite": "seeds", "suite_hash": "x", "done": 3})";
  EXPECT_THROW(calibrate_error_model((root / "run0").string()), InputError)
      << "a recorded run of another suite file";
}

}  // namespace
}  // namespace dv
