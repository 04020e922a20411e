// Shape rows' verdicts (shape_verdict.h) on synthetic runs of known effect: the paper's ratio
// inside our interval, within the band, a ratio that differs, rows that are not comparable (the
// paper prints no number, 0 against 0 in the paper or in ours, nothing measured), an overhead
// (a difference) and the table's sentence; claims on two sides that measure 0 (not comparable,
// not a tie); the practical band of differences (a difference
// smaller than the band is a tie, named in the basis); claims' timers (the result names its
// timer, rows without the timer are not comparable, a claim the paper's way cannot test says so)
// and the suite loader's errors for a claim without a timer or with one its rows do not carry.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "experiments/harness/findings.h"
#include "experiments/harness/shape_verdict.h"
#include "experiments/harness/suite_file.h"
#include "tests/experiments/synthetic_runs.h"

namespace dv {
namespace {

using test::reps;
using test::Runs;

// Two timed items over three runs: `side=a` takes `ratio` times as long as `side=b` (10 ms),
// the per-run ratio off by -1 %, 0, +1 % (a t-interval of about ratio x [0.975, 1.025]).
std::vector<RunView> timed_pair(Runs& runs, double ratio) {
  const double off[3] = {0.99, 1.0, 1.01};
  std::vector<std::vector<double>> a, b;
  for (double o : off) {
    a.push_back(reps(10.0 * ratio * o));
    b.push_back(reps(10.0));
  }
  runs.timed(0, "side=a", "generate_ms", a);
  runs.timed(1, "side=b", "generate_ms", b);
  return runs.views();
}

Comparison ours(const std::vector<RunView>& views, bool difference = false,
                const std::string& second = "side=b") {
  const Column c{"generate_ms", "median"};
  return compare_selections("side=a", c, second, c, views, 1, difference);
}

TEST(ShapeVerdicts, ThePapersRatioInsideOurIntervalWithinTheBandOrNot) {
  Runs runs(3);
  const Comparison c = ours(timed_pair(runs, 2.0));
  ASSERT_TRUE(c.has_interval);
  EXPECT_NEAR(c.interval.effect, 2.0, 0.001);
  EXPECT_GT(c.interval.high, 2.04);
  EXPECT_LT(c.interval.high, 2.06);
  const ShapeVerdict inside = shape_verdict(20.0, 10.0, c, false, 0.1);
  EXPECT_EQ(inside.kind, ShapeVerdict::Kind::inside);
  EXPECT_EQ(inside.text, "reproduces (inside our interval)");
  // 2.2 lies above the interval, within 10 % of its upper end; not within 5 %.
  const ShapeVerdict near = shape_verdict(2.2, 1.0, c, false, 0.1);
  EXPECT_EQ(near.kind, ShapeVerdict::Kind::within_band);
  EXPECT_EQ(near.text, "reproduces (within ±10 %)");
  EXPECT_TRUE(near.reproduces());
  const ShapeVerdict far = shape_verdict(2.2, 1.0, c, false, 0.05);
  EXPECT_EQ(far.kind, ShapeVerdict::Kind::differs);
  EXPECT_EQ(far.text, "differs (ours 0.909x the paper's)");
  EXPECT_FALSE(far.reproduces());
  // Below: the paper's ratio 1.5 against our 2.
  EXPECT_EQ(shape_verdict(3.0, 2.0, c, false, 0.1).text, "differs (ours 1.33x the paper's)");
}

TEST(ShapeVerdicts, NotComparableWhereASideIsMissingOrZeroAgainstZero) {
  Runs runs(3);
  const std::vector<RunView> views = timed_pair(runs, 2.0);
  const Comparison c = ours(views);
  EXPECT_EQ(shape_verdict(std::nan(""), 10.0, c, false, 0.1).text,
            "not comparable (the paper prints no number on a side)");
  EXPECT_EQ(shape_verdict(0.0, 0.0, c, false, 0.1).text,
            "not comparable (0 against 0 in the paper)");
  EXPECT_EQ(shape_verdict(5.0, 0.0, c, false, 0.1).text,
            "not comparable (the paper's ratio divides by 0)");
  const ShapeVerdict unmeasured = shape_verdict(2.0, 1.0, ours(views, false, "side=c"), false, 0.1);
  EXPECT_EQ(unmeasured.kind, ShapeVerdict::Kind::not_comparable);
  EXPECT_EQ(unmeasured.text, "not comparable (ours: no measured item matches the second side)");
  // A count that is 0 on both sides in every run (wasted chunks where nothing races): our ratio
  // is 0 against 0, which the comparison itself leaves without a verdict.
  Runs zeros(3);
  zeros.value(0, "side=a", "wasted", 0.0);
  zeros.value(1, "side=b", "wasted", 0.0);
  const Column w{"wasted", "value"};
  const Comparison none = compare_selections("side=a", w, "side=b", w, zeros.views(), 1);
  EXPECT_EQ(none.verdict, "not comparable (0 against 0: both sides measure 0)");
  EXPECT_EQ(shape_verdict(3.0, 4.0, none, false, 0.1).text, "not comparable (0 against 0 in ours)");
  // One side 0, the other not: a difference where the paper gives a ratio.
  Runs one_zero(3);
  one_zero.value(0, "side=a", "wasted", 2.0);
  one_zero.value(1, "side=b", "wasted", 0.0);
  EXPECT_EQ(
      shape_verdict(3.0, 4.0, compare_selections("side=a", w, "side=b", w, one_zero.views(), 1),
                    false, 0.1)
          .text,
      "not comparable (ours is a difference: a side is 0 in some run)");
}

// An overhead row: the paper's frame minus its no-shadow frame against our difference.
TEST(ShapeVerdicts, OverheadsAreDifferences) {
  Runs runs(3);
  const Comparison c = ours(timed_pair(runs, 1.2), true);  // 12 - 10 ms, +-1 %
  ASSERT_TRUE(c.has_interval);
  EXPECT_FALSE(c.interval.ratio);
  EXPECT_NEAR(c.interval.effect, 2.0, 1e-9);
  EXPECT_EQ(shape_verdict(45.0, 43.0, c, true, 0.1).kind, ShapeVerdict::Kind::inside);
  EXPECT_EQ(shape_verdict(45.5, 43.0, c, true, 0.1).kind, ShapeVerdict::Kind::within_band);
  EXPECT_EQ(shape_verdict(50.0, 43.0, c, true, 0.1).text, "differs (ours lower by 5)");
}

TEST(ShapeVerdicts, OneSentencePerTableNamesWhatReproducesAndTheLoads) {
  const auto row = [](const std::string& what, ShapeVerdict::Kind kind, const std::string& text,
                      double first, double second) {
    return ShapeRow{what, {kind, text}, first, second, true};
  };
  const std::vector<ShapeRow> rows{
      row("gen, 512 / 256", ShapeVerdict::Kind::inside, "reproduces (inside our interval)", 4.1,
          2.0),
      row("gen, 1024 / 512", ShapeVerdict::Kind::within_band, "reproduces (within ±10 %)", 9.0,
          4.1),
      row("render, 512 / 256", ShapeVerdict::Kind::differs, "differs (ours 0.5x the paper's)", 1.0,
          0.95),
      row("filtered, 512 / 256", ShapeVerdict::Kind::not_comparable,
          "not comparable (the paper prints no number on a side)", 0.0, 0.0)};
  EXPECT_EQ(shape_sentence(rows, 0.1),
            "2 of 4 rows reproduce the paper (1 inside our 95 % interval, 1 within ±10 %): gen, "
            "512 / 256; gen, 1024 / 512; 1 differs: render, 512 / 256 (ours 0.5x the paper's); 1 "
            "not comparable (filtered, 512 / 256). Our loads: 2–9 ms where the rows reproduce, "
            "0.95–1 ms where they differ.");
}

// Probe errors of two items, the first 0.0005 T below the second at every point.
std::vector<RunView> error_pair(Runs& runs) {
  std::vector<double> a, b;
  for (int k = 0; k < 40; ++k) {
    a.push_back(0.01 + 0.0002 * k);
    b.push_back(0.0105 + 0.0002 * k);
  }
  runs.errors(0, "eps=0.01", "medium", a);
  runs.errors(1, "eps=0.02", "medium", b);
  return runs.views();
}

const char* kErrorClaim = R"([{"claim": "finer eps errs less", "timer": "none",
  "lower": ["eps=0.01", "probe_error_medium:mean"],
  "than": ["eps=0.02", "probe_error_medium:mean"]}])";

TEST(PracticalBands, ADifferenceWithinTheBandIsATie) {
  Runs runs(1);
  const std::vector<RunView> views = error_pair(runs);
  const auto claim = nlohmann::json::parse(kErrorClaim);
  const FindingResult plain = evaluate_findings(claim, views)[0];
  EXPECT_EQ(plain.verdict, "confirmed");
  EXPECT_EQ(plain.effect, "-0.0005 [-0.0005, -0.0005]");
  // Stated per column, or per metric for every statistic of it.
  for (const PracticalBands& bands : {PracticalBands{{"probe_error_medium:mean", 0.001}},
                                      PracticalBands{{"probe_error_medium", 0.001}}}) {
    const FindingResult r = evaluate_findings(claim, views, {}, bands)[0];
    EXPECT_EQ(r.verdict, "tie");
    EXPECT_NE(r.basis.find("; practical band ±0.001 T (suite)"), std::string::npos) << r.basis;
  }
  // Narrower than the difference: still decided.
  EXPECT_EQ(evaluate_findings(claim, views, {}, {{"probe_error_medium:mean", 0.0004}})[0].verdict,
            "confirmed");
  // A band of another statistic does not apply; the column's own entry wins over its metric's.
  EXPECT_EQ(evaluate_findings(claim, views, {}, {{"probe_error_medium:p99", 0.01}})[0].verdict,
            "confirmed");
  EXPECT_EQ(practical_band({{"m", 0.5}, {"m:mean", 0.25}}, {"m", "mean"}), 0.25);
  EXPECT_EQ(practical_band({{"m", 0.5}}, {"m", "max"}), 0.5);
  EXPECT_EQ(practical_band({}, {"m", "max"}), 0.0);
}

// A claim whose two sides measure 0 (a count that stays 0, errors exact on both) says nothing:
// not comparable, not a tie; a trend with such a step says which.
TEST(ZeroAgainstZero, ClaimsOnTwoZerosAreNotComparable) {
  Runs runs(3);
  runs.value(0, "alloc=aggregated", "wasted", 0.0);
  runs.value(1, "alloc=thesis", "wasted", 0.0);
  runs.value(2, "alloc=pooled", "wasted", 3.0);
  runs.errors(0, "alloc=aggregated", "medium", {0.0, 0.0, 0.0});
  runs.errors(1, "alloc=thesis", "medium", {0.0, -0.0, 0.0});
  const std::vector<RunView> views = runs.views();
  const auto verdict = [&](const std::string& json) {
    return evaluate_findings(nlohmann::json::parse(json), views)[0].verdict;
  };
  EXPECT_EQ(verdict(R"([{"claim": "fewer wasted", "timer": "none",
    "lower": ["alloc=aggregated", "wasted"], "than": ["alloc=thesis", "wasted"]}])"),
            "not comparable (0 against 0: both sides measure 0)");
  EXPECT_EQ(verdict(R"([{"claim": "errs less", "timer": "none",
    "lower": ["alloc=aggregated", "probe_error_medium:mean"],
    "than": ["alloc=thesis", "probe_error_medium:mean"]}])"),
            "not comparable (0 against 0: both sides measure 0)");
  // 0 against 3: a difference, decided.
  EXPECT_EQ(verdict(R"([{"claim": "fewer wasted", "timer": "none",
    "lower": ["alloc=aggregated", "wasted"], "than": ["alloc=pooled", "wasted"]}])"),
            "confirmed");
  EXPECT_EQ(verdict(R"([{"claim": "grows", "trend": "increasing", "over": "alloc",
    "levels": ["aggregated", "thesis", "pooled"], "selector": "", "timer": "none",
    "column": "wasted"}])"),
            "not comparable (step aggregated → thesis: not comparable (0 against 0: both sides "
            "measure 0))");
}

TEST(ClaimTimers, TheResultNamesItsTimerAndRowsWithoutItAreNotComparable) {
  Runs runs(3);
  const std::vector<RunView> views = timed_pair(runs, 0.5);
  const FindingResult r = evaluate_findings(nlohmann::json::parse(R"([{"claim": "a faster",
    "timer": "generate_ms", "lower": ["side=a", "generate_ms:median"],
    "than": ["side=b", "generate_ms:median"]}])"),
                                            views)[0];
  EXPECT_EQ(r.timer, "generate_ms");
  EXPECT_EQ(r.verdict, "confirmed");
  const FindingResult missing = evaluate_findings(nlohmann::json::parse(R"([{"claim": "a faster",
    "timer": "generate.generation_ms", "lower": ["side=a", "generate.generation_ms:median"],
    "than": ["side=b", "generate.generation_ms:median"]}])"),
                                                  views)[0];
  EXPECT_EQ(missing.verdict, "not comparable (no row carries the timer generate.generation_ms)");
  const FindingResult trend = evaluate_findings(nlohmann::json::parse(R"([{"claim": "grows",
    "trend": "increasing", "over": "side", "levels": ["b", "a"], "selector": "",
    "timer": "generate.passes.count_ms", "column": "generate.passes.count_ms:median"}])"),
                                                views)[0];
  EXPECT_EQ(trend.verdict, "not comparable (no row carries the timer generate.passes.count_ms)");
  // A claim the paper's way cannot test: the reason, then our verdict on what we have.
  const FindingResult unlike = evaluate_findings(nlohmann::json::parse(R"([{"claim": "a faster",
    "timer": "generate_ms", "not_as_paper": "the paper timed a pass our rows do not carry",
    "lower": ["side=a", "generate_ms:median"], "than": ["side=b", "generate_ms:median"]}])"),
                                                 views)[0];
  EXPECT_EQ(unlike.verdict,
            "cannot be tested as the paper did: the paper timed a pass our rows do not carry "
            "(ours: confirmed)");
}

// The loader's message for `finding` (the one claim of a one-experiment suite), or "" when the
// suite loads.
std::string load_error(const std::string& finding) {
  const std::string text = R"({"suite": "t", "experiments": [{"name": "a", "kind": "shadow",
    "scene": "s.json", "strategy": "none", "findings": [)" +
                           finding + "]}]}";
  try {
    parse_suite(text, "timers.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ClaimTimers, TheSuiteLoaderWantsEveryClaimToNameTheTimerItsRowsCarry) {
  const std::string sides =
      R"("lower": ["strategy=none", "generate_ms:median"], "than": ["", "generate_ms:median"])";
  EXPECT_EQ(load_error(R"({"claim": "none faster", "timer": "generate_ms", )" + sides + "}"), "");
  const std::string no_timer = load_error(R"({"claim": "none faster", )" + sides + "}");
  EXPECT_NE(no_timer.find("timers.json"), std::string::npos) << no_timer;
  EXPECT_NE(no_timer.find("findings/0/timer"), std::string::npos) << no_timer;
  EXPECT_NE(no_timer.find("the claim 'none faster' names no timer"), std::string::npos) << no_timer;
  const std::string other =
      load_error(R"({"claim": "none faster", "timer": "frame_ms", )" + sides + "}");
  EXPECT_NE(other.find("the claim 'none faster': its rows carry generate_ms and generate_ms, not "
                       "the timer 'frame_ms' it names"),
            std::string::npos)
      << other;
  const std::string none =
      load_error(R"({"claim": "none faster", "timer": "none", )" + sides + "}");
  EXPECT_NE(none.find("compares a time (generate_ms)"), std::string::npos) << none;
  EXPECT_NE(load_error(R"({"claim": "fewer bytes", "timer": "bytes", "lower": ["", "bytes"],
                          "than": ["", "bytes"]})")
                .find("is not a time metric"),
            std::string::npos);
  EXPECT_EQ(load_error(R"({"claim": "fewer bytes", "timer": "none", "lower": ["", "bytes"],
                          "than": ["", "bytes"]})"),
            "");
  const std::string trend = load_error(R"({"claim": "grows", "trend": "increasing", "over": "res",
    "selector": "", "column": "generate_ms:median"})");
  EXPECT_NE(trend.find("the claim 'grows' names no timer"), std::string::npos) << trend;
  EXPECT_NE(
      load_error(R"({"claim": "x", "timer": "generate_ms", "not_as_paper": "", )" + sides + "}")
          .find("not_as_paper"),
      std::string::npos);
}

// A result folder records its suite as it ran: one recorded before claims named their timers is
// read by `deepvox report` with each claim's timer taken from the one metric its columns
// compare ("none" where they compare no time); the hash stays the recorded text's.
TEST(ClaimTimers, ResultFoldersRecordedBeforeTimersStillReport) {
  const std::string text = R"({"suite": "t", "experiments": [{"name": "a", "kind": "shadow",
    "scene": "s.json", "strategy": "none", "findings": [
      {"claim": "none faster", "lower": ["strategy=none", "generate_ms:median"],
       "than": ["", "generate_ms:median"]},
      {"claim": "fewer bytes", "lower": ["", "bytes"], "than": ["", "bytes"]},
      {"claim": "grows", "trend": "increasing", "over": "res", "selector": "",
       "column": "frame_ms:median"}]}]})";
  EXPECT_THROW(parse_suite(text, "recorded.json"), InputError);
  const Suite s = parse_recorded_suite(text, "recorded.json");
  const nlohmann::json& findings = s.experiments[0].findings;
  EXPECT_EQ(findings[0]["timer"], "generate_ms");
  EXPECT_EQ(findings[1]["timer"], "none");
  EXPECT_EQ(findings[2]["timer"], "frame_ms");
  const std::string named =
      R"({"suite": "t", "experiments": [{"name": "a", "kind": "shadow", "scene": "s.json",
    "strategy": "none", "findings": [{"claim": "none faster", "timer": "generate_ms",
    "lower": ["strategy=none", "generate_ms:median"], "than": ["", "generate_ms:median"]}]}]})";
  EXPECT_EQ(parse_recorded_suite(named, "named.json").hash, parse_suite(named, "named.json").hash);
}

TEST(PracticalBands, TheSuiteStatesThemPerMetric) {
  const auto load = [](const std::string& bands) {
    return parse_suite(R"({"suite": "t", "practical_bands": )" + bands +
                           R"(, "experiments": [{"name": "a", "kind": "shadow",
      "scene": "s.json", "strategy": "none"}]})",
                       "bands.json");
  };
  const Suite s = load(R"({"probe_error_all:mean": 0.002, "image_rmse": 0.001})");
  EXPECT_EQ(s.practical_bands.at("probe_error_all:mean"), 0.002);
  EXPECT_EQ(s.practical_bands.at("image_rmse"), 0.001);
  EXPECT_THROW(load(R"({"image_rmse": 0})"), InputError);
  EXPECT_THROW(load(R"({"image_rmse": "1 %"})"), InputError);
  EXPECT_THROW(load(R"([0.001])"), InputError);
}

}  // namespace
}  // namespace dv
