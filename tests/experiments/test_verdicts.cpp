// The findings' verdicts from effect sizes with 95 % intervals (findings.h, effect_interval.h),
// on synthetic samples: a confirmation, a refutation, a tie (also one that only drift between
// runs makes a tie), paired probe errors, a monotone trend and a plateau, a defect, claims that
// are not comparable, the Student-t interval over runs (its quantiles, runs that lack an item,
// one run that gives no verdict), a reproducible paired bootstrap; a report over a result folder
// from before samples/ (it still builds, its timing claims say the interval is unavailable) and
// over three recorded runs; a shape table (the paper's ratios beside ours with intervals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "experiments/harness/aa_controls.h"
#include "experiments/harness/effect_interval.h"
#include "experiments/harness/findings.h"
#include "experiments/harness/recorded_runs.h"
#include "experiments/harness/report.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/runner.h"
#include "experiments/harness/student_t.h"
#include "experiments/source_paths.h"
#include "tests/experiments/harness_test.h"
#include "tests/experiments/synthetic_runs.h"

namespace dv {
namespace {

namespace fs = std::filesystem;
using test::reps;
using test::Runs;

FindingResult one(const std::string& json, std::vector<RunView> views) {
  const std::vector<FindingResult> r = evaluate_findings(nlohmann::json::parse(json), views);
  EXPECT_EQ(r.size(), 1u);
  return r.empty() ? FindingResult{} : r[0];
}

const char* kChunkedFaster = R"([{"claim": "chunked faster",
  "lower": ["storage=chunked", "generate_ms:median"],
  "than": ["storage=texture3d", "generate_ms:median"], "why": "fewer layers",
  "why_not": "pools first"}])";

TEST(Verdicts, ClearlyLowerInEveryRunIsConfirmed) {
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.0), reps(2.1), reps(1.9)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.2), reps(3.8)});
  const FindingResult f = one(kChunkedFaster, runs.views());
  EXPECT_EQ(f.verdict, "confirmed");
  EXPECT_NE(f.effect.find("0.5x ["), std::string::npos) << f.effect;
  EXPECT_EQ(f.basis, "3 runs x 5 repetitions, 1 vs 1 items");
  EXPECT_NE(f.explanation.find("reading: fewer layers"), std::string::npos) << f.explanation;
}

TEST(Verdicts, ClearlyHigherIsRefuted) {
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(5.0), reps(5.1), reps(4.9)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.1), reps(3.9)});
  const FindingResult f = one(kChunkedFaster, runs.views());
  EXPECT_EQ(f.verdict, "refuted");
  EXPECT_NE(f.explanation.find("; pools first"), std::string::npos) << f.explanation;
}

TEST(Verdicts, OverlappingRepetitionsAreATieNotAConfirmation) {
  // The old rule (mean below mean) called this confirmed: 2.99 against 3.00.
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.99), reps(3.0), reps(2.98)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(3.0), reps(3.01), reps(2.99)});
  const FindingResult f = one(kChunkedFaster, runs.views());
  EXPECT_EQ(f.verdict, "tie");
  EXPECT_NE(f.explanation.find("; pools first"), std::string::npos) << f.explanation;
}

TEST(Verdicts, DriftBetweenRunsWidensTheInterval) {
  // Within each run chunked looks 5 % faster or 5 % slower; one run alone would decide.
  Runs drift(3);
  drift.timed(0, "storage=chunked", "generate_ms", {reps(2.85), reps(3.15), reps(2.85)});
  drift.timed(1, "storage=texture3d", "generate_ms", {reps(3.0), reps(3.0), reps(3.0)});
  EXPECT_EQ(one(kChunkedFaster, drift.views()).verdict, "tie");
  // One run alone has no spread between runs: no verdict, and the report says why.
  Runs single(1);
  single.timed(0, "storage=chunked", "generate_ms", {reps(2.85)});
  single.timed(1, "storage=texture3d", "generate_ms", {reps(3.0)});
  const FindingResult f = one(kChunkedFaster, single.views());
  EXPECT_EQ(f.verdict,
            "not comparable (1 run: a t-interval over runs needs at least 2; run the suite with "
            "--runs 5)");
  EXPECT_EQ(f.basis, "1 run x 5 repetitions, 1 vs 1 items");
  EXPECT_EQ(f.lower, side_mean({{reps(2.85)}}));  // the means are still shown
}

TEST(Verdicts, RunsLackingAnItemAreLeftOut) {
  // Item 0 was not measured in the third run: two complete runs remain.
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.0), reps(2.1)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.2), reps(3.8)});
  const FindingResult f = one(kChunkedFaster, runs.views());
  EXPECT_EQ(f.verdict, "confirmed");
  EXPECT_EQ(f.basis,
            "2 runs x 5 repetitions, 1 vs 1 items (1 more left out: an item of a side was not "
            "measured in them)");
  EXPECT_NE(f.effect.find("0.5x [0.5, 0.5]"), std::string::npos) << f.effect;
}

TEST(Verdicts, ProbeErrorsArePairedOverThePoints) {
  // The points differ wildly from one another, but at every point the first side errs 0.01
  // less: an unpaired interval would hold 0, the paired one does not.
  std::vector<double> a, b;
  for (int k = 0; k < 200; ++k) {
    const double base = 0.1 * double(k % 10);
    a.push_back(k % 2 ? base : -base);
    b.push_back(k % 2 ? base + 0.01 : -base - 0.01);
  }
  Runs runs(1);
  runs.errors(0, "eps=0.01", "medium", a);
  runs.errors(1, "eps=0.2", "medium", b);
  const FindingResult f = one(R"([{"claim": "smaller eps errs less",
    "lower": ["eps=0.01", "probe_error_medium:mean"],
    "than": ["eps=0.2", "probe_error_medium:mean"]}])",
                              runs.views());
  EXPECT_EQ(f.verdict, "confirmed");
  EXPECT_NE(f.effect.find("-0.01 [-0.01, -0.01]"), std::string::npos) << f.effect;
  EXPECT_NE(f.basis.find("200 probe errors per item (paired"), std::string::npos) << f.basis;
  // The "all" class pools every class of the samples.
  const FindingResult all = one(R"([{"claim": "all", "lower": ["eps=0.01", "probe_error_all:mean"],
    "than": ["eps=0.2", "probe_error_all:mean"]}])",
                                runs.views());
  EXPECT_EQ(all.verdict, "confirmed");
  EXPECT_EQ(all.effect, f.effect);
}

const char* kLayersDecrease = R"([{"claim": "fewer layers at a larger eps",
  "trend": "decreasing", "over": "eps", "selector": "clusters=4",
  "column": "stats.storage.mean_layers_nonempty"}])";

TEST(Verdicts, MonotoneTrendTestsEveryStep) {
  Runs runs(2);
  const std::vector<std::pair<std::string, double>> layers{
      {"0.2", 3.0}, {"0.01", 4.0}, {"0.05", 3.6}, {"0.1", 3.3}};  // sorted by eps, not by order
  for (size_t i = 0; i < layers.size(); ++i)
    runs.value(int(i), "eps=" + layers[i].first + " clusters=4",
               "stats.storage.mean_layers_nonempty", layers[i].second);
  const FindingResult f = one(kLayersDecrease, runs.views());
  EXPECT_EQ(f.verdict, "confirmed");
  ASSERT_EQ(f.steps.size(), 3u);
  EXPECT_EQ(f.steps[0].from, "0.01");
  EXPECT_EQ(f.steps[2].to, "0.2");
  EXPECT_NE(f.effect.find("0.01 → 0.05: 0.9x [0.9, 0.9]"), std::string::npos) << f.effect;
  // One step up in the middle: the two endpoints still agree, the trend does not.
  Runs bump(2);
  const std::vector<std::pair<std::string, double>> bumped{
      {"0.01", 4.0}, {"0.05", 3.3}, {"0.1", 3.6}, {"0.2", 3.0}};
  for (size_t i = 0; i < bumped.size(); ++i)
    bump.value(int(i), "eps=" + bumped[i].first + " clusters=4",
               "stats.storage.mean_layers_nonempty", bumped[i].second);
  EXPECT_EQ(one(kLayersDecrease, bump.views()).verdict, "refuted");
}

TEST(Verdicts, PlateauFromALevelOn) {
  Runs runs(2);
  const std::vector<std::pair<std::string, double>> max_layers{
      {"0.01", 28}, {"0.05", 21}, {"0.1", 21}, {"0.2", 21}};
  for (size_t i = 0; i < max_layers.size(); ++i)
    runs.value(int(i), "eps=" + max_layers[i].first, "stats.storage.max_layers",
               max_layers[i].second);
  const char* plateau = R"([{"claim": "max layers plateau from eps 0.05", "trend": "plateau",
    "over": "eps", "from": 0.05, "selector": "", "column": "stats.storage.max_layers"}])";
  const FindingResult f = one(plateau, runs.views());
  EXPECT_EQ(f.verdict, "tie");  // "no difference" holds: a tie, never "confirmed"
  EXPECT_EQ(f.explanation.rfind("2 of 2 tested steps flat (from eps=0.05)", 0), 0u)
      << f.explanation;
  // From 0.01 on the first step moves: no plateau there.
  const FindingResult early = one(R"([{"claim": "c", "trend": "plateau", "over": "eps",
    "from": 0.01, "selector": "", "column": "stats.storage.max_layers"}])",
                                  runs.views());
  EXPECT_EQ(early.verdict, "refuted");
  // Decreasing over the whole sweep: one step down, two flat steps: a tie, not a confirmation.
  const FindingResult down = one(R"([{"claim": "c", "trend": "decreasing", "over": "eps",
    "selector": "", "column": "stats.storage.max_layers"}])",
                                 runs.views());
  EXPECT_EQ(down.verdict, "tie");
  // A level that the sweep lacks.
  const FindingResult missing = one(R"([{"claim": "c", "trend": "plateau", "over": "eps",
    "from": 0.3, "selector": "", "column": "stats.storage.max_layers"}])",
                                    runs.views());
  EXPECT_EQ(missing.verdict.rfind("not comparable (the plateau's level 0.3", 0), 0u)
      << missing.verdict;
}

TEST(Verdicts, LossyRowsMakeADefect) {
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.0), reps(2.0), reps(2.0)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.0), reps(4.0)});
  runs.value(0, "storage=chunked", "stats.storage.overflowed_texels", 12);
  runs.value(1, "storage=texture3d", "stats.tiles.dropped_tiles", 0);  // 0: no loss
  const FindingResult f = one(kChunkedFaster, runs.views());
  EXPECT_EQ(f.verdict,
            "defect (item 0: stats.storage.overflowed_texels = 12; 1 of 2 items lossy: the "
            "measurement lost data)");
  EXPECT_EQ(f.effect, "-");
}

TEST(Verdicts, ExpectedLossIsDecidedAndNamed) {
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.0), reps(2.0), reps(2.0)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.0), reps(4.0)});
  runs.value(1, "storage=texture3d", "stats.storage.overflowed_texels", 7);
  nlohmann::json claim = nlohmann::json::parse(kChunkedFaster);
  claim[0]["lossy"] = "expected";
  const std::vector<FindingResult> f = evaluate_findings(claim, runs.views());
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].verdict, "confirmed");
  EXPECT_NE(f[0].basis.find("lossy as the claim expects (item 1: "
                            "stats.storage.overflowed_texels = 7; 1 of 2 items lossy)"),
            std::string::npos)
      << f[0].basis;
}

TEST(Verdicts, ACountWithinOnePercentIsATie) {
  // Mean layers that do not vary between runs: a zero-width interval at 1.005x is no effect,
  // 1.05x is one.
  const char* more = R"([{"claim": "more layers at res 512",
    "lower": ["res=256", "stats.storage.mean_layers"],
    "than": ["res=512", "stats.storage.mean_layers"]}])";
  Runs close(3);
  close.value(0, "res=256", "stats.storage.mean_layers", 2.0, "layers");
  close.value(1, "res=512", "stats.storage.mean_layers", 2.01, "layers");
  EXPECT_EQ(one(more, close.views()).verdict, "tie");
  Runs apart(3);
  apart.value(0, "res=256", "stats.storage.mean_layers", 2.0, "layers");
  apart.value(1, "res=512", "stats.storage.mean_layers", 2.1, "layers");
  EXPECT_EQ(one(more, apart.views()).verdict, "confirmed");
}

TEST(Verdicts, NotComparable) {
  Runs runs(3);
  runs.timed(0, "storage=chunked", "generate_ms", {reps(2.0), reps(2.0), reps(2.0)});
  runs.timed(1, "storage=texture3d", "generate_ms", {reps(4.0), reps(4.0), reps(4.0)});
  runs.value(0, "storage=chunked", "bytes", 10, "bytes");
  EXPECT_EQ(one(R"([{"claim": "c", "lower": ["storage=blocked", "generate_ms:median"],
    "than": ["", "generate_ms:median"]}])",
                runs.views())
                .verdict,
            "not comparable (no measured item matches the first side)");
  EXPECT_EQ(one(R"([{"claim": "c", "lower": ["storage=chunked", "bytes"],
    "than": ["storage=texture3d", "generate_ms:median"]}])",
                runs.views())
                .verdict,
            "not comparable (units differ: bytes vs ms)");
  // A result folder from before samples/: rows alone give no interval for a timing.
  runs.drop_samples();
  const FindingResult old = one(kChunkedFaster, runs.views());
  EXPECT_EQ(old.verdict.rfind("not comparable (2 items without per-repetition samples: interval "
                              "unavailable",
                              0),
            0u)
      << old.verdict;
  EXPECT_EQ(old.lower, 2.0);  // the means are still shown
}

TEST(Verdicts, StudentTIntervalOverRuns) {
  // Quantiles against published tables (97.5 %: 12.706 with 1 degree of freedom, 4.303 with 2,
  // 2.776 with 4, 2.228 with 10, 1.960 in the limit).
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062047, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.3026527, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.7764451, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 10), 2.2281389, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.995, 1), 63.6567412, 1e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 1e6), 1.9599640, 1e-5);
  EXPECT_NEAR(student_t_quantile(0.025, 3), -student_t_quantile(0.975, 3), 1e-12);
  EXPECT_NEAR(student_t_cdf(student_t_quantile(0.9, 7), 7), 0.9, 1e-12);
  // Differences 1, 2, 3: mean 2, standard deviation 1, half-width t(0.975, 2) / sqrt(3).
  const EffectInterval d = t_interval({1.0, 2.0, 3.0}, false);
  EXPECT_FALSE(d.ratio);
  EXPECT_DOUBLE_EQ(d.effect, 2.0);
  EXPECT_NEAR(d.high - d.effect, 4.3026527 / std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(d.effect - d.low, 4.3026527 / std::sqrt(3.0), 1e-6);
  // Ratios 2 and 8: the geometric mean 4, the interval symmetric on the log scale.
  const EffectInterval r = t_interval({2.0, 8.0}, true);
  EXPECT_TRUE(r.ratio);
  EXPECT_NEAR(r.effect, 4.0, 1e-12);
  EXPECT_NEAR(std::log(r.high / 4.0), 12.7062047 * std::log(4.0) / 2.0, 1e-6);
  EXPECT_NEAR(r.low * r.high, 16.0, 1e-9);
  // Per run the sides' means: runs 2.0 / 2.4, 2.3 / 2.2; the third run lacks the second item.
  const std::vector<RunSamples> a{{reps(2.0), reps(2.3), reps(1.8)}, {reps(2.0), reps(2.3)}};
  const std::vector<RunSamples> b{{reps(2.4), reps(2.2), reps(2.6)}};
  const RunInterval two = run_interval(a, b);
  EXPECT_EQ(two.runs, 2u);
  const EffectInterval expected = t_interval({2.0 / 2.4, 2.3 / 2.2}, true);
  EXPECT_DOUBLE_EQ(two.interval.effect, expected.effect);
  EXPECT_DOUBLE_EQ(two.interval.low, expected.low);
  EXPECT_DOUBLE_EQ(two.interval.high, expected.high);
  EXPECT_EQ(run_interval({{reps(2.0)}}, {{reps(3.0)}}).runs, 1u);  // no interval
  // A side whose mean is 0 in a run: the differences instead.
  const RunInterval zero = run_interval({{{0.0}, {0.0}}}, {{{2.0}, {3.0}}});
  EXPECT_FALSE(zero.interval.ratio);
  EXPECT_DOUBLE_EQ(zero.interval.effect, -2.5);
  EXPECT_EQ(seed_of("claim"), seed_of("claim"));
  EXPECT_NE(seed_of("claim"), seed_of("claim."));
  // The paired bootstrap: the same seed, the same interval; another seed, other draws.
  const std::vector<double> f1{0.1, -0.5, 0.2, 0.9, -0.3}, f2{0.2, -0.1, 0.4, 0.3, -0.6};
  const EffectInterval p7 = paired_bootstrap({{&f1, "s"}}, {{&f2, "s"}}, "mean", 7);
  const EffectInterval q7 = paired_bootstrap({{&f1, "s"}}, {{&f2, "s"}}, "mean", 7);
  const EffectInterval p8 = paired_bootstrap({{&f1, "s"}}, {{&f2, "s"}}, "mean", 8);
  EXPECT_EQ(std::make_pair(p7.low, p7.high), std::make_pair(q7.low, q7.high));
  EXPECT_LT(p7.low, p7.effect);
  EXPECT_GT(p7.high, p7.effect);
  EXPECT_EQ(p8.effect, p7.effect);
  EXPECT_NE(std::make_pair(p8.low, p8.high), std::make_pair(p7.low, p7.high));
  // p99 and max of |error|, paired: the same draws on both sides.
  const std::vector<double> e1{0.1, -0.2, 0.3, -0.4}, e2{0.2, -0.3, 0.4, -0.5};
  const EffectInterval m = paired_bootstrap({{&e1, "s"}}, {{&e2, "s"}}, "max", 3);
  EXPECT_FALSE(m.ratio);
  EXPECT_DOUBLE_EQ(m.effect, -0.1);
  EXPECT_DOUBLE_EQ(m.low, -0.1);
  EXPECT_DOUBLE_EQ(m.high, -0.1);
}

// A/A pairs whose copy / original ratio is 1, 1.02, 0.97 and 1.05, +-0.2 % from run to run,
// while the runs drift together: narrow intervals, 3 of 4 outside the 1 % band; the tie band is
// their 95th percentile of |log ratio| (here the largest, about 5 %), which no pair then
// exceeds.
TEST(AaControls, TieBandFromTheSpreadAndTheFalsePositiveRate) {
  Runs runs(5);
  const std::vector<double> copy_ratio{1.0, 1.02, 0.97, 1.05};
  const std::vector<double> drift{1.0, 1.1, 0.95, 1.03, 0.9};
  for (int pair = 0; pair < 4; ++pair) {
    const std::string params = "res=" + std::to_string(16 << pair);
    std::vector<std::vector<double>> original, copy;
    for (size_t r = 0; r < drift.size(); ++r) {
      const double wobble = r % 2 ? 0.998 : 1.002;
      original.push_back(reps(2.0 * (pair + 1) * drift[r]));
      copy.push_back(reps(2.0 * (pair + 1) * drift[r] * copy_ratio[size_t(pair)] * wobble));
    }
    runs.timed(pair, params, "generate_ms", original);
    runs.timed(10 + pair, params + " aa=copy", "generate_ms", copy);
  }
  const std::vector<RunView> views = runs.views();
  const AaControls aa = measure_aa_controls(views);
  ASSERT_EQ(aa.pairs.size(), 4u);
  EXPECT_EQ(aa.pairs[1].original, 1);
  EXPECT_EQ(aa.pairs[1].copy, 11);
  EXPECT_EQ(aa.runs, 5u);
  EXPECT_EQ(aa.tested, 4);
  EXPECT_EQ(aa.outside, 3);
  EXPECT_EQ(aa.outside_tie_band, 0);
  ASSERT_EQ(aa.tie_bands.count("generate_ms"), 1u);
  EXPECT_NEAR(aa.tie_bands.at("generate_ms"), 0.05, 1e-3);
  EXPECT_EQ(aa_rate_text(aa),
            "3 of 4 A/A intervals (75 %) exclude no effect (goal <= 5 %); with the tie bands "
            "from the A/A spread 0 of 4 (0 %); 4 pairs, 5 runs");
  EXPECT_EQ(tie_bands_text(aa), "generate_ms ±5 % (4 pairs)");
  // A 3 % effect: confirmed against the fixed 1 % band, a tie inside the A/A band of 5 %.
  Runs claim(3);
  claim.timed(0, "storage=chunked", "generate_ms", {reps(2.91), reps(3.1), reps(2.81)});
  claim.timed(1, "storage=texture3d", "generate_ms", {reps(3.0), reps(3.2), reps(2.9)});
  const std::vector<RunView> claim_views = claim.views();
  const auto findings = nlohmann::json::parse(kChunkedFaster);
  EXPECT_EQ(evaluate_findings(findings, claim_views)[0].verdict, "confirmed");
  const FindingResult banded = evaluate_findings(findings, claim_views, aa.tie_bands)[0];
  EXPECT_EQ(banded.verdict, "tie");
  EXPECT_NE(banded.basis.find("; tie band ±5 % (A/A)"), std::string::npos) << banded.basis;
  // No copies, or copies measured in one run only: said so.
  EXPECT_EQ(aa_rate_text(measure_aa_controls(claim_views)),
            "none (no experiment sets \"aa_duplicates\")");
  const std::vector<RunView> first_only(views.begin(), views.begin() + 1);
  EXPECT_EQ(aa_rate_text(measure_aa_controls(first_only)),
            "4 A/A pairs, no interval: they need timings in at least 2 runs");
}

// The report of the first run with the second recorded beside it (runs.json), as text.
std::string pooled_report(const SuiteOutcome& first, const SuiteOutcome& second) {
  record_runs(first.folder, {second.folder});
  build_report(first.folder);
  std::ifstream in(fs::path(first.folder) / "report.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class AaReport : public test::HarnessTest {};

// A suite run twice on the CPU with A/A copies: rows.csv marks the copies, the report's header
// prints the A/A false-positive rate and the experiment its tie bands.
TEST_F(AaReport, HeaderPrintsTheFalsePositiveRateAndTheExperimentItsTieBands) {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  const std::string suite = write("aa.json", R"({"suite": "tiny-aa", "repeat": 2,
    "experiments": [{"name": "dsm", "kind": "shadow", "scene": ")" +
                                                 scene + R"(", "aa_duplicates": true,
      "strategy": ["none", {"name": "dsm", "params": {"res": 32}}],
      "settings": {"width": 32, "height": 24, "probe_points": 0, "images": 0},
      "findings": [{"claim": "no shadows generate faster",
                    "lower": ["strategy=none", "generate_ms:median"],
                    "than": ["strategy=dsm", "generate_ms:median"],
                    "timer": "generate_ms"}]}]})");
  const SuiteOptions o = cpu_options(suite);
  const SuiteOutcome r = run_suite(o), r2 = run_suite(o);
  ASSERT_EQ(r.exit_code, 0);
  ASSERT_EQ(r2.exit_code, 0);
  int copies = 0;
  for (const Row& row : read_rows_csv(r.folder + "/rows.csv"))
    copies += row.metric == "generate_ms" && row.stat == "median" &&
              row.params.find("aa=copy") != std::string::npos;
  EXPECT_EQ(copies, 2);
  const std::string md = pooled_report(r, r2);
  const size_t rate = md.find("- A/A false-positive rate: ");
  ASSERT_NE(rate, std::string::npos) << md;
  EXPECT_LT(rate, md.find("## "));  // at the top, before the first experiment
  EXPECT_NE(md.find(" A/A intervals (", rate), std::string::npos) << md;
  EXPECT_NE(md.find("; 2 pairs, 2 runs", rate), std::string::npos) << md;
  EXPECT_NE(md.find("A/A controls (`aa_duplicates`): "), std::string::npos) << md;
  EXPECT_NE(md.find("tie bands from the A/A spread: "), std::string::npos) << md;
  EXPECT_NE(md.find("generate_ms ±"), std::string::npos) << md;
  EXPECT_NE(md.find("- practical bands (a difference whose interval lies within one is a tie): "
                    "none stated (suite practical_bands): differences tie only at 0"),
            std::string::npos)
      << md;
}

class OldFolders : public test::HarnessTest {};

// The rest of the line of `md` that begins with `start` (from it on), or "" when none does.
std::string line_from(const std::string& md, const std::string& start) {
  const size_t at = md.find(start);
  return at == std::string::npos ? "" : md.substr(at, md.find('\n', at) - at);
}

// A folder written before samples/ (here: its samples removed) still reports; its timing claim
// says why it has no interval, its byte claim (rows alone) still decides.
TEST_F(OldFolders, ReportWithoutSamplesStillBuilds) {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  const std::string suite = write("tiny.json", R"({"suite": "tiny-old", "repeat": 2,
    "experiments": [{"name": "dsm", "kind": "shadow", "scene": ")" +
                                                   scene + R"(",
      "strategy": ["none", {"name": "dsm", "params": {"res": 32}}],
      "settings": {"width": 32, "height": 24, "probe_points": 20, "images": 0},
      "findings": [{"claim": "no shadows are cheaper", "lower": ["strategy=none", "bytes"],
                    "than": ["strategy=dsm", "bytes"], "timer": "none"},
                   {"claim": "no shadows generate faster",
                    "lower": ["strategy=none", "generate_ms:median"],
                    "than": ["strategy=dsm", "generate_ms:median"], "timer": "generate_ms"},
                   {"claim": "no shadows err less", "lower": ["strategy=none", "probe_error_all:mean"],
                    "than": ["strategy=dsm", "probe_error_all:mean"], "timer": "none"}]}]})");
  SuiteOptions o = cpu_options(suite);
  const SuiteOutcome r = run_suite(o);
  ASSERT_EQ(r.exit_code, 0);
  const fs::path dir(r.folder);
  ASSERT_TRUE(fs::is_regular_file(dir / "samples" / "0.json"));
  const auto samples = nlohmann::json::parse(std::ifstream(dir / "samples" / "1.json"));
  EXPECT_EQ(samples["timings"]["generate_ms"].size(), 2u);
  EXPECT_EQ(samples["timings"]["frame_ms"].size(), 2u);
  const size_t probes =
      samples["probe_errors"]["surface"].size() + samples["probe_errors"]["medium"].size();
  EXPECT_GT(probes, 0u);
  EXPECT_EQ(probes % 20, 0u);  // 20 points, each per light
  // probe_error_all pools the world-uniform classes; the findings' "all" takes the same ones.
  EXPECT_EQ(samples["probe_all"], nlohmann::json({"surface", "medium"}));
  auto report = [&] {
    build_report(dir.string());
    std::ifstream in(dir / "report.md");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  std::string md = report();
  EXPECT_NE(md.find("rest on 1 independent process run (this folder); a t-interval over runs "
                    "needs at least 2"),
            std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| - | 1 run x 2 repetitions, 1 vs 1 items | generate_ms | not comparable (1 run: a "
              "t-interval over runs needs at least 2"),
      std::string::npos)
      << md;
  fs::remove_all(dir / "samples");
  md = report();
  EXPECT_NE(md.find("| no shadows are cheaper |"), std::string::npos) << md;
  EXPECT_NE(md.find("| - | 1 run x 1 value, 1 vs 1 items | none | not comparable (1 run: "),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("not comparable (2 items without per-repetition samples: interval "
                    "unavailable (a result folder from before samples/))"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("not comparable (no probe samples for item 0: interval unavailable"),
            std::string::npos)
      << md;
  // Two more runs recorded by name: the report pools three.
  const SuiteOutcome r2 = run_suite(o), r3 = run_suite(o);
  record_runs(dir.string(), {r2.folder, r3.folder});
  md = report();
  EXPECT_NE(md.find("rest on 3 independent process runs (this folder and those runs.json names); "
                    "95 % t-intervals over the per-run effects"),
            std::string::npos)
      << md;
  // The bytes of no shadows are 0 in every run: the difference, the same in every run.
  const std::string line = line_from(md, "| no shadows are cheaper |");
  ASSERT_FALSE(line.empty()) << md;
  EXPECT_NE(line.find(" [-"), std::string::npos) << line;
  EXPECT_NE(line.find("| 3 runs x 1 value, 1 vs 1 items | none | confirmed |"), std::string::npos)
      << line;
  // The tables and plots show every run: each value the median over the three runs, a timing's
  // min and max the lowest and highest run median (rows_over_runs.csv, which the plots read).
  EXPECT_NE(md.find("- tables and plots: over the 3 runs: each cell the median of the runs' "
                    "values"),
            std::string::npos)
      << md;
  const auto value_of = [](const std::vector<Row>& rows, int item, const std::string& metric,
                           const std::string& stat) {
    for (const Row& row : rows)
      if (row.item == item && row.metric == metric && row.stat == stat) return row.value;
    ADD_FAILURE() << "no row " << item << " " << metric << ":" << stat;
    return 0.0;
  };
  const std::vector<Row> shown = read_rows_csv((dir / "rows_over_runs.csv").string());
  std::vector<double> frames, generations;
  for (const std::string& run : {dir.string(), r2.folder, r3.folder}) {
    const std::vector<Row> rows = read_rows_csv((fs::path(run) / "rows.csv").string());
    frames.push_back(value_of(rows, 1, "frame_ms", "value"));
    generations.push_back(value_of(rows, 1, "generate_ms", "median"));
  }
  std::sort(frames.begin(), frames.end());
  EXPECT_DOUBLE_EQ(value_of(shown, 1, "frame_ms", "value"), frames[1]);
  EXPECT_DOUBLE_EQ(value_of(shown, 1, "generate_ms", "min"),
                   *std::min_element(generations.begin(), generations.end()));
  EXPECT_DOUBLE_EQ(value_of(shown, 1, "generate_ms", "max"),
                   *std::max_element(generations.begin(), generations.end()));
  EXPECT_DOUBLE_EQ(value_of(shown, 1, "bytes", "value"),
                   value_of(read_rows_csv((dir / "rows.csv").string()), 1, "bytes", "value"));
  EXPECT_THROW(record_runs(dir.string(), {(dir_ / "nowhere").string()}), InputError);
  // One run again: no such file.
  std::ofstream(dir / "runs.json") << R"({"runs": []})";
  report();
  EXPECT_FALSE(fs::exists(dir / "rows_over_runs.csv"));
}

// A mapped paper table with a "shape": the paper's ratios beside ours with intervals, across the
// sweep, within the table and above the no-shadow frame of another experiment.
TEST_F(OldFolders, ShapeTablePutsThePapersRatiosBesideOurs) {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  write("shape-table.json", R"({"source": "Tiny 2024, Table 2", "machine": "an abacus",
    "units": {"*": "ms"}, "columns": ["", "16", "32"],
    "rows": [["gen", 10, 20], ["render", 50, 55]]})");
  const std::string suite = write("shape.json", R"({"suite": "tiny-shape", "repeat": 2,
    "experiments": [
     {"name": "base", "kind": "shadow", "scene": ")" +
                                                    scene + R"(", "strategy": "none",
      "settings": {"width": 32, "height": 24, "probe_points": 0, "images": 0}},
     {"name": "dsm", "kind": "shadow", "scene": ")" +
                                                    scene + R"(", "strategy": "dsm",
      "sweep": {"res": [16, 32]},
      "settings": {"width": 32, "height": 24, "probe_points": 0, "images": 0},
      "paper": [{"table": "shape-table.json", "where": "",
                 "rows": [["", "generate_ms:median"], ["", "render_ms:median"]],
                 "columns": ["res=16", "res=32"],
                 "shape": {"machine": "Abacus to silicon predicts nothing.",
                           "column_pairs": [[1, 0]], "row_pairs": [[1, 0]],
                           "baseline": {"selector": "experiment=base",
                                        "column": "render_ms:median", "paper": 43,
                                        "source": "Tiny's text", "rows": [1]}}}]}]})");
  SuiteOptions o = cpu_options(suite);
  const SuiteOutcome r = run_suite(o), r2 = run_suite(o);
  ASSERT_EQ(r.exit_code, 0);
  ASSERT_EQ(r2.exit_code, 0);
  const std::string md = pooled_report(r, r2);
  EXPECT_NE(md.find("overhead above the no-shadow frame: the paper's 43 ms (Tiny's text)"),
            std::string::npos)
      << md;
  for (const char* line :
       {"| gen, 32 / 16 | 2x | ", "| render, 32 / 16 | 1.1x | ", "| render / gen, 16 | 5x | ",
        "| render / gen, 32 | 2.75x | ", "| render, 16 − the no-shadow frame | 7 | ",
        "| render, 32 − the no-shadow frame | 12 | "}) {
    const std::string rest = line_from(md, line);
    ASSERT_FALSE(rest.empty()) << line << "\n" << md;
    EXPECT_NE(rest.find(" ["), std::string::npos) << rest;  // ours with its interval
    EXPECT_NE(rest.find("2 runs x 2 repetitions"), std::string::npos) << rest;
    // Each row's verdict: the paper's ratio against our interval (CPU timings decide which).
    EXPECT_TRUE(rest.find("| reproduces (inside our interval) |") != std::string::npos ||
                rest.find("| reproduces (within ±10 %) |") != std::string::npos ||
                rest.find("| differs (ours ") != std::string::npos)
        << rest;
  }
  EXPECT_NE(md.find("| ratio | paper | ours [95 % interval] | interval rests on | verdict |"),
            std::string::npos)
      << md;
  // One sentence under the table: how many of its 6 rows reproduce, which, and at what loads.
  const std::string text = line_from(md, "Shape verdicts: ");
  ASSERT_FALSE(text.empty()) << md;
  EXPECT_NE(text.find(" of 6 rows reproduce the paper ("), std::string::npos) << text;
  EXPECT_NE(text.find(" within ±10 %)"), std::string::npos) << text;
  EXPECT_NE(text.find(". Our loads: "), std::string::npos) << text;
  EXPECT_NE(md.find("Machine change: Abacus to silicon predicts nothing."), std::string::npos)
      << md;
  // A shape that names a row the map lacks is rejected when the suite loads.
  const std::string text_of_suite = [&] {
    std::ifstream f(suite);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }();
  std::string broken = text_of_suite;
  broken.replace(broken.find("\"rows\": [1]"), 12, "\"rows\": [5]");
  EXPECT_THROW(run_suite(cpu_options(write("bad-shape.json", broken))), InputError);
}

}  // namespace
}  // namespace dv
