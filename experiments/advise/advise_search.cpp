// The search space, the coarse-to-fine walk, the front and the pick (advise_search.h).
#include "experiments/advise/advise_search.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "strategies/shadow/strategy_catalog.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

ShadowConfig config_at(const std::vector<AdviseFamily>& space, const AdvisePoint& point) {
  const AdviseFamily& f = space.at(size_t(point.family));
  ShadowConfig c{f.method, f.fixed};
  for (size_t a = 0; a < f.axes.size(); ++a)
    c.params[f.axes[a].key] = f.axes[a].values.at(size_t(point.at.at(a)));
  return c;
}

bool AdviseBudgets::within_cost(const AdviseMeasurement& m) const {
  return (!frame_ms || m.frame_ms <= *frame_ms) && (!bytes || m.bytes <= *bytes);
}

bool AdviseBudgets::within_error(const AdviseMeasurement& m) const {
  return m.error_p95 <= error && (!image_error || m.image_edge <= *image_error);
}

bool AdviseBudgets::met_by(const AdviseMeasurement& m) const {
  return m.ok && within_error(m) && within_cost(m);
}

Stratum AdviseMeasurement::worst_stratum() const {
  Stratum worst = Stratum::lit;
  for (Stratum s : kAllStrata)
    if (strata[size_t(s)].judged() > strata[size_t(worst)].judged()) worst = s;
  return worst;
}

void AdviseMeasurement::add_fresh_points(const AdviseMeasurement& fresh) {
  rejected_at_fresh_points = true;
  if (!fresh.ok) {
    ok = false;
    failure = "at fresh points: " + fresh.failure;
    return;
  }
  for (size_t s = 0; s < kStrata; ++s)
    if (fresh.strata[s].judged() > strata[s].judged()) strata[s] = fresh.strata[s];
  error_p95 = std::max(error_p95, fresh.error_p95);
  error_max = std::max(error_max, fresh.error_max);
  shadows_measured = shadows_measured && fresh.shadows_measured;
}

bool dominates(const AdviseMeasurement& a, const AdviseMeasurement& b) {
  if (!a.ok || !b.ok) return false;
  const bool no_worse =
      a.error_p95 <= b.error_p95 && a.frame_ms <= b.frame_ms && a.bytes <= b.bytes;
  const bool better = a.error_p95 < b.error_p95 || a.frame_ms < b.frame_ms || a.bytes < b.bytes;
  return no_worse && better;
}

std::vector<size_t> advise_front(const std::vector<AdviseResult>& results) {
  std::vector<size_t> front;
  for (size_t i = 0; i < results.size(); ++i) {
    const AdviseMeasurement& m = results[i].measurement;
    if (!m.ok || !std::isfinite(m.error_p95) || !std::isfinite(m.frame_ms)) continue;
    bool dominated = false;
    for (size_t j = 0; j < results.size() && !dominated; ++j)
      dominated = j != i && dominates(results[j].measurement, m);
    if (!dominated) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(), [&](size_t a, size_t b) {
    return results[a].measurement.frame_ms < results[b].measurement.frame_ms;
  });
  return front;
}

std::vector<size_t> advise_picks(const std::vector<AdviseResult>& results,
                                 const AdviseBudgets& budgets) {
  std::vector<size_t> picks;
  for (size_t i = 0; i < results.size(); ++i)
    if (budgets.met_by(results[i].measurement)) picks.push_back(i);
  std::stable_sort(picks.begin(), picks.end(), [&](size_t a, size_t b) {
    const AdviseMeasurement &x = results[a].measurement, &y = results[b].measurement;
    return x.frame_ms != y.frame_ms ? x.frame_ms < y.frame_ms : x.bytes < y.bytes;
  });
  return picks;
}

std::vector<size_t> timing_contenders(const std::vector<AdviseResult>& results,
                                      const std::vector<size_t>& picks, double band, size_t most) {
  std::vector<size_t> contenders;
  for (size_t i : picks) {
    if (contenders.size() == most) break;
    if (!contenders.empty() &&
        results[i].measurement.frame_ms > band * results[contenders.front()].measurement.frame_ms)
      break;
    contenders.push_back(i);
  }
  return contenders;
}

std::vector<std::vector<size_t>> interleaved_rounds(size_t n, int rounds) {
  std::vector<std::vector<size_t>> order(size_t(std::max(rounds, 0)));
  for (size_t r = 0; r < order.size(); ++r)
    for (size_t k = 0; k < n; ++k) order[r].push_back((r + k) % n);
  return order;
}

namespace {

bool should_stop(const AdviseSearchLimits& limits, size_t measured) {
  return int(measured) >= limits.max_evaluations || (limits.stop && limits.stop());
}

AdviseResult measured(const std::vector<AdviseFamily>& space, const AdvisePoint& p,
                      const AdviseMeasure& measure) {
  AdviseResult r{p, config_at(space, p), {}};
  r.measurement = measure(r.config);
  return r;
}

// The neighbours of `p` one step along one axis: coarser (-1) and, when `finer`, finer (+1).
std::vector<AdvisePoint> neighbours(const std::vector<AdviseFamily>& space, const AdvisePoint& p,
                                    bool finer) {
  std::vector<AdvisePoint> out;
  const AdviseFamily& f = space[size_t(p.family)];
  for (size_t a = 0; a < f.axes.size(); ++a)
    for (int step : {-1, 1}) {
      if (step > 0 && !finer) continue;
      AdvisePoint q = p;
      q.at[a] += step;
      if (q.at[a] >= 0 && q.at[a] < int(f.axes[a].values.size())) out.push_back(q);
    }
  return out;
}

// A storage's family of the space: res, and its size knob at eps 0.01 where it has one (from
// the knob's registered default on), else eps, filter and clusters where it keeps the error
// bound eps (compact), else res alone (beer).
AdviseFamily advise_storage_family(const CatalogEntry& storage, const AdviseAxis& res) {
  AdviseFamily f{"dsm " + storage.name, "dsm", {{"storage", storage.name}}, {res}, {1}};
  const StrategyTraits& t = storage.traits;
  if (!t.size_key.empty()) {
    // The knob's default (the registered one) is the start; eps is fine enough that the
    // storage's own size, not the node compression, limits the error.
    std::string fallback;
    for (const ParamSpec& spec : storage.params)
      if (spec.key == t.size_key) fallback = spec.fallback;
    const auto start = std::find(t.sizes.begin(), t.sizes.end(), fallback);
    f.fixed["eps"] = "0.01";
    f.axes.push_back({"storage." + t.size_key, t.sizes});
    f.start.push_back(start == t.sizes.end() ? 0 : int(start - t.sizes.begin()));
  } else if (storage_registry().create(storage.name)->keeps_error_bound()) {
    f.axes.push_back({"eps", {"0.2", "0.05", "0.02", "0.01", "0.005", "0.002"}});
    f.axes.push_back({"filter", {"none", "bilinear"}});
    f.axes.push_back({"clusters", {"1", "4"}});
    f.start = {1, 1, 0, 0};
  }
  return f;
}

}  // namespace

std::vector<AdviseResult> advise_search(const std::vector<AdviseFamily>& space,
                                        const AdviseBudgets& budgets, const AdviseMeasure& measure,
                                        const AdviseSearchLimits& limits,
                                        const AdviseProgress& progress,
                                        std::vector<AdviseResult> earlier) {
  std::vector<AdviseResult> results = std::move(earlier);
  std::set<AdvisePoint> seen;
  for (const AdviseResult& r : results) seen.insert(r.point);
  std::vector<AdvisePoint> queue;
  for (size_t f = 0; f < space.size(); ++f) queue.push_back({int(f), space[f].start});
  while (!queue.empty()) {
    for (const AdvisePoint& p : queue) {
      if (!seen.insert(p).second) continue;
      if (should_stop(limits, results.size())) return results;
      results.push_back(measured(space, p, measure));
      if (progress) progress(results);
    }
    queue.clear();
    // Expand the front only: a dominated point's branch ends here. A point the fresh points
    // rejected is expanded too, dominated or not: the configurations just finer than one that
    // looked good are the likely ones.
    std::vector<size_t> expand = advise_front(results);
    for (size_t i = 0; i < results.size(); ++i)
      if (results[i].measurement.rejected_at_fresh_points) expand.push_back(i);
    for (size_t i : expand) {
      const AdviseMeasurement& m = results[i].measurement;
      const bool finer =
          (!budgets.within_error(m) || !m.shadows_measured) && budgets.within_cost(m);
      for (const AdvisePoint& q : neighbours(space, results[i].point, finer))
        if (!seen.count(q)) queue.push_back(q);
    }
  }
  return results;
}

std::vector<AdviseResult> advise_sweep(const std::vector<AdviseFamily>& space,
                                       const AdviseMeasure& measure,
                                       const AdviseSearchLimits& limits,
                                       const AdviseProgress& progress) {
  std::vector<AdviseResult> results;
  for (size_t f = 0; f < space.size(); ++f) {
    AdvisePoint p{int(f), std::vector<int>(space[f].axes.size(), 0)};
    while (true) {  // every index vector of the family, odometer order
      if (should_stop(limits, results.size())) return results;
      results.push_back(measured(space, p, measure));
      if (progress) progress(results);
      size_t a = 0;
      for (; a < p.at.size(); ++a) {
        if (++p.at[a] < int(space[f].axes[a].values.size())) break;
        p.at[a] = 0;
      }
      if (a == p.at.size()) break;
    }
  }
  return results;
}

std::vector<AdviseFamily> advise_space(const AdviseSceneKind& kind) {
  const AdviseAxis res{"res", {"128", "256", "512", "1024", "2048"}};
  if (!kind.translucent && !kind.media)
    return {{"shadowmap", "shadowmap", {}, {res, {"pcf", {"1", "3"}}}, {1, 0}}};
  std::vector<AdviseFamily> space;
  for (const CatalogEntry& storage : catalog_of("storage")) {
    if (!storage.traits.not_advised.empty()) continue;
    space.push_back(advise_storage_family(storage, res));
  }
  space.push_back({"transmittance-slicemap",
                   "transmittance-slicemap",
                   {},
                   {{"res", {"256", "512", "1024"}}, {"slices", {"32", "64", "128"}}},
                   {0, 0}});
  return space;
}

}  // namespace dv
