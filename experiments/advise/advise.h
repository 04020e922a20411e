// `deepvox advise` as a library: on the user's scene, the coarse-to-fine search
// (advise_search.h) over shadow configurations measured against the exact oracle
// (advise_measure.h), the Pareto front, the cheapest configuration that meets the error bound
// and the budgets (the near-cheapest candidates timed again in interleaved rounds, so that
// timing jitter does not decide a near tie), verified on fresh probe points (another seed than
// the search's: a candidate whose verified error misses the bound gives way to the next
// cheapest, three per round; when a round rejects them all, their fresh errors are folded into
// their measurements and the search resumes from the corrected front for a few more
// measurements, a few rounds at most),
// and the outputs: a table, JSON, a shadow config file and an SVG plot (advise_report.h).
// The error is judged per stratum of the probe points (advise_measure.h). Unless asked for speed
// only or given an image bound, the default configuration (`auto` with its defaults) is measured
// too and its image edge error bounds the pick's: advise never picks a configuration whose
// image is worse than the defaults' (the default itself is a candidate).
// `--shadows auto --error-budget` runs it too, over the configurations `auto` takes, for a
// scene its error model cannot predict. Ctrl-C (interrupt.h) ends the search; what was
// measured is kept and the pick is made from it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cuda/execute.h"
#include "experiments/advise/advise_measure.h"
#include "experiments/advise/advise_search.h"

namespace dv {

class SceneCache;

// The verification's points: the search's seed plus this (a seed the search never uses).
inline constexpr uint64_t kVerifySeedOffset = 1000003;
// The final timing (timing_contenders): the candidates within this factor of the cheapest
// one's search time, at most this many, timed again in interleaved rounds.
inline constexpr double kFinalTimingBand = 1.5;
inline constexpr size_t kFinalTimingMost = 6;
// After a round of verification that rejected its candidates, the search resumes from the
// corrected front for at most this many more measurements, at most this many times.
inline constexpr int kResumeEvaluations = 8;
inline constexpr int kResumedRounds = 4;
// The default configuration: what render takes without shadow options.
ShadowConfig default_shadow_config();

struct AdviseOptions {
  std::string scene;
  AdviseBudgets budgets;
  AdviseSettings settings;
  int max_evaluations = 60;
  bool exhaustive = false;  // measure every point of the space (the search's check)
  bool auto_only = false;   // only what the auto method takes (its dsm parameters)
  int max_res = 0;          // > 0: no map resolution above it (small machines)
  int final_rounds = 5;     // interleaved rounds of the final timing; 0: none
  bool speed_only = false;  // no image bound unless budgets.image_error names one
  // A line per measurement ("[12] dsm compact res=512 ...: p95 0.004, 1.2 ms"), for progress.
  std::function<void(const std::string&)> progress;
};

struct Advice {
  // A contender of the final timing: its time per interleaved round and their median.
  struct FinalTiming {
    size_t index = 0;  // into results
    std::vector<double> times_ms;
    double median_ms = 0.0;
  };
  std::vector<AdviseResult> results;      // in measuring order
  std::vector<FinalTiming> final_timing;  // empty when fewer than two contenders
  std::vector<size_t> front;              // advise_front(results)
  std::optional<size_t> pick;             // the verified pick, when one is
  std::optional<size_t> tried;            // the last candidate verified (pick or not)
  std::optional<size_t> default_index;    // the default configuration's result, when measured
  AdviseBudgets budgets;                  // the options' with the image bound applied
  AdviseMeasurement verified;             // its measurement at fresh points
  uint64_t verify_seed = 0;
  std::string strata_counts, verified_strata_counts;  // StratifiedProbes::counts_text
  int light_count = 0;
  int width = 0, height = 0;
  bool interrupted = false;
  double seconds = 0.0;
  // The frame time the choice of results[index] rests on: the final timing's median where it
  // was timed there, else the search's measurement.
  double chosen_ms(size_t index) const;
};

// The search's space on `measurer`'s scene (auto_only: the families as the auto method with the
// same parameters; max_res > 0: the res axes cut there).
std::vector<AdviseFamily> advise_space_for(const AdviseMeasurer& measurer, bool auto_only,
                                           int max_res);
Advice advise(SceneCache& cache, const AdviseOptions& options);

}  // namespace dv
