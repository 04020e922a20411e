// The search of `deepvox advise`, independent of how a configuration is measured:
// the space of shadow configurations (per family a method with fixed parameters and ordered
// axes, coarse to fine: resolution, eps, filter, clusters, a basis storage's size), a
// coarse-to-fine walk over it that stops a branch once it is dominated, the Pareto front of the
// measured points and the pick under an error bound and budgets.
// The walk starts at each family's coarse start point, measures, and expands only the
// unmeasured neighbours (one axis one step) of the points on the front (error, frame time,
// bytes): a dominated point's branch ends. A front point that meets the error bound and the
// budgets is refined only towards coarser (cheaper) neighbours; one that breaks the time or
// memory budget likewise; the others both ways, and so does one whose shadow strata are not
// measured (AdviseMeasurement::shadows_measured: no early stop on a false zero). It ends when
// nothing is left to expand, after `max_evaluations`, or when `stop` says so (Ctrl-C, a deadline):
// what was measured is kept.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "experiments/harness/probe_strata.h"
#include "strategies/shadow/shadow_config.h"

namespace dv {

struct AdviseAxis {
  std::string key;                  // a parameter of the family's method
  std::vector<std::string> values;  // coarse (cheap, less accurate) to fine
};

struct AdviseFamily {
  std::string name;    // "dsm compact", "shadowmap", ...
  std::string method;  // a shadow method
  std::map<std::string, std::string> fixed;
  std::vector<AdviseAxis> axes;
  std::vector<int> start;  // per axis, the coarse start
};

// A point of a family's space: one value index per axis.
struct AdvisePoint {
  int family = 0;
  std::vector<int> at;
  bool operator<(const AdvisePoint& o) const {
    return family != o.family ? family < o.family : at < o.at;
  }
  bool operator==(const AdvisePoint& o) const { return family == o.family && at == o.at; }
};

ShadowConfig config_at(const std::vector<AdviseFamily>& space, const AdvisePoint& point);

// What measuring one configuration gives (advise_measure.h fills it). The error is per stratum
// of the probe points (probe_strata.h): error_p95 is the worst stratum's judged figure (its p95,
// its max where it has too few samples for a p95), what the bound is checked against.
struct AdviseMeasurement {
  bool ok = false;                          // false: it failed (failure says why), never on a front
  std::string failure;                      // e.g. a storage's limit
  double error_p95 = 0.0, error_max = 0.0;  // over the strata: the worst judged p95, the max
  std::array<StratumError, kStrata> strata{};
  // Every shadow stratum that holds samples has enough for a p95, and some shadow stratum
  // holds samples where the lights reach casters: a zero error is not a false zero.
  bool shadows_measured = true;
  double image_rmse = 0.0;
  double image_edge = 0.0;  // image_metrics.h's edge error against the reference render
  double frame_ms = 0.0;    // median generation + median render, warm
  double bytes = 0.0;
  // Set when a verification at fresh points missed the bound: the figures above then hold the
  // worse of the search's and the fresh points' (add_fresh_points).
  bool rejected_at_fresh_points = false;
  // The stratum of the worst judged error (lit when every one is 0).
  Stratum worst_stratum() const;
  // Folds in a measurement of the same configuration at fresh points that missed the bound:
  // per stratum the worse judged error, the worse p95 and max, and the mark, so that the front,
  // the picks and a resumed search see what the fresh points saw.
  void add_fresh_points(const AdviseMeasurement& fresh);
};

struct AdviseResult {
  AdvisePoint point;
  ShadowConfig config;
  AdviseMeasurement measurement;
};

struct AdviseBudgets {
  double error = 0.02;                // per stratum: p95 |T' - T| (the max where too few samples)
  std::optional<double> image_error;  // most image_edge (advise: by default the default's)
  std::optional<double> frame_ms;     // --budget-ms
  std::optional<double> bytes;        // --memory-mb, in bytes
  bool within_cost(const AdviseMeasurement& m) const;
  bool within_error(const AdviseMeasurement& m) const;  // the probe error and the image bound
  bool met_by(const AdviseMeasurement& m) const;        // ok, error and costs
};

// Whether `a` dominates `b`: both measured, a no worse in error (p95), frame time and bytes and
// better in one.
bool dominates(const AdviseMeasurement& a, const AdviseMeasurement& b);
// Indices of the results no other result dominates (failures excluded), by frame time.
std::vector<size_t> advise_front(const std::vector<AdviseResult>& results);
// The indices of the results that meet `budgets`, cheapest first (frame time, then bytes): the
// pick is the first one its verification confirms.
std::vector<size_t> advise_picks(const std::vector<AdviseResult>& results,
                                 const AdviseBudgets& budgets);

// The final timing of advise (advise.h): of `picks` (advise_picks' order), the leading ones whose
// search time is within `band` times the first's, at most `most`; these are timed again in
// interleaved rounds, since one search measurement of a frame of about a millisecond varies
// between measurements by more than the near ties it would decide (clock and launch jitter).
std::vector<size_t> timing_contenders(const std::vector<AdviseResult>& results,
                                      const std::vector<size_t>& picks, double band, size_t most);
// The order of `rounds` interleaved rounds over n configurations: every round times each once,
// its start rotating by one per round, so that each configuration takes every place in turn
// and a drift over the rounds falls on all of them alike.
std::vector<std::vector<size_t>> interleaved_rounds(size_t n, int rounds);

struct AdviseSearchLimits {
  int max_evaluations = 60;
  std::function<bool()> stop;  // checked before each measurement; may be empty
};

using AdviseMeasure = std::function<AdviseMeasurement(const ShadowConfig&)>;
// Called after each measurement: the results so far and the one just added.
using AdviseProgress = std::function<void(const std::vector<AdviseResult>&)>;

// The coarse-to-fine walk (see the file comment); results in measuring order. `earlier`
// continues a walk: its points are not measured again, and its front (as its measurements now
// read, e.g. after add_fresh_points) and its points rejected at fresh points are expanded; the
// limits count its results too.
std::vector<AdviseResult> advise_search(const std::vector<AdviseFamily>& space,
                                        const AdviseBudgets& budgets, const AdviseMeasure& measure,
                                        const AdviseSearchLimits& limits,
                                        const AdviseProgress& progress = {},
                                        std::vector<AdviseResult> earlier = {});
// Every point of the space measured (the exhaustive sweep `advise --exhaustive` runs as the
// search's check), within the same limits.
std::vector<AdviseResult> advise_sweep(const std::vector<AdviseFamily>& space,
                                       const AdviseMeasure& measure,
                                       const AdviseSearchLimits& limits,
                                       const AdviseProgress& progress = {});

// What kind of casters a scene's lights reach decides the families worth searching.
struct AdviseSceneKind {
  bool translucent = false;  // some light reaches a caster with 0 < alpha < 1
  bool media = false;        // some light reaches a constant medium or a volume
};
// The search space: shadow maps when every reached caster is opaque; otherwise every registered
// DSM storage whose traits do not leave it out (strategy_catalog.h): one with a size knob over
// resolution and its size (avsm, moments, fourier, occupancy), one that keeps the error bound
// over resolution, eps, filter and clusters (compact), the others over resolution (beer); and
// the transmittance slice map.
std::vector<AdviseFamily> advise_space(const AdviseSceneKind& kind);

}  // namespace dv
