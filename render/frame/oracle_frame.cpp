// The deferred oracle pass's rounds and its pass of exact shadow queries (see oracle_passes.h).
#include <algorithm>
#include <string>

#include "cuda/sort.h"
#include "engine/oracle/transmittance.h"
#include "engine/scene/volume_sampling.h"
#include "render/frame/oracle_passes.h"

namespace dv {

namespace {

int key_bits_for(int64_t lights) {
  int bits = 1;
  while ((int64_t(1) << bits) < lights) ++bits;
  return bits;
}

// The answer pass's register budget (parallel_for_bounded): its chains of dependent
// double-precision operations stall on their latency, which more resident warps hide. Four
// blocks of 256 threads per SM (64 registers) answered knecht-fig56's queries in 12.75 ms, three
// (85) in 13.47, two (128) in 16.01 and the occupancy calculator's launch (164 registers) in
// 20.97; knecht-32-lights 379 / 407 / 484 / 619 ms (H100, results/perf/2026-12-06-deferred-oracle).
constexpr int kAnswerMinBlocks = 4;

// The sort key's cost bits: the samples a march would take along the query's shadow ray in
// bricks that are not empty (occupied_brick_length over each volume's step), at most 2^16 - 1.
constexpr uint32_t kCostBits = 16;

// A query's cost estimate: queries of about the same cost share a warp, so that its lanes walk
// about as many volume cells (the ray from the point towards the light, beyond it too, which
// lies outside the volumes for lights outside them; an estimate only orders the work).
DV_HD inline uint32_t oracle_query_cost(const SceneView& s, const OracleQuery& q) {
  const LightView& l = s.lights[q.light];
  dvec3 dir = l.type == LightType::directional ? -l.direction : l.position - q.point;
  const double len = glm::length(dir);
  if (!(len > 0.0)) return 0;
  dir /= len;
  double samples = 0.0;
  for (int64_t k = 0; k < s.objects.size; ++k) {
    const ObjectView& o = s.objects[k];
    if (o.interior == InteriorKind::volume)
      samples += occupied_brick_length(s, o, q.point, dir, 0.0) / o.step;
  }
  const double most = double((1u << kCostBits) - 1);
  return uint32_t(samples < most ? samples : most);  // a NaN counts as the most
}

}  // namespace

nlohmann::json OracleFrameStats::stats() const {
  return {{"queries", queries},    {"rounds", rounds},       {"buffer_bytes", buffer_bytes},
          {"count_ms", count_ms},  {"record_ms", record_ms}, {"answer_ms", answer_ms},
          {"replay_ms", replay_ms}};
}

std::vector<std::pair<int64_t, int64_t>> plan_oracle_rounds(const std::vector<int64_t>& starts,
                                                            int64_t threads, int64_t per_round) {
  std::vector<std::pair<int64_t, int64_t>> rounds;
  int64_t first = 0;
  while (first < threads) {
    int64_t end = std::min(first + 32, threads);
    while (end < threads) {
      const int64_t next = std::min(end + 32, threads);
      if (starts[size_t(next)] - starts[size_t(first)] > per_round) break;
      end = next;
    }
    rounds.emplace_back(first, end);
    first = end;
  }
  return rounds;
}

// The queries in the order of the key (light, cost), heaviest first, equal keys in pixel and
// sample order (a stable sort): a warp's lanes leave one light and walk about as many cells.
void answer_oracle_queries(Backend backend, const SceneView& scene, View<const OracleQuery> queries,
                           View<OracleAnswer> answers, int64_t n) {
  if (n == 0) return;
  const int key_bits = key_bits_for(scene.lights.size) + int(kCostBits);
  if (key_bits > 32)
    throw Error("oracle frame: " + std::to_string(scene.lights.size) +
                " lights do not fit the 32-bit query key (at most 65,536)");
  const Memory memory = memory_of(backend);
  Buffer<uint32_t> keys(memory, n, "oracle query keys");
  Buffer<int32_t> index(memory, n, "oracle query index");
  Buffer<int32_t> ordered(memory, n, "oracle queries in key order");
  const View<uint32_t> k = keys.view();
  const View<int32_t> i = index.view();
  parallel_for(
      backend, "oracle_query_keys", n, DV_KERNEL_LAMBDA(int64_t q) {
        k[q] = (uint32_t(queries[q].light) << kCostBits) | oracle_query_cost(scene, queries[q]);
        i[q] = int32_t(q);
      });
  sort_by_key_descending_queued(backend, keys.const_view(), index.const_view(), ordered.view(),
                                key_bits);
  const View<const int32_t> order = ordered.const_view();
  parallel_for_bounded<kAnswerMinBlocks>(
      backend, "oracle_answers", n, DV_KERNEL_LAMBDA(int64_t j) {
        const int64_t q = order[j];
        const OracleQuery query = queries[q];
        const OracleResult r = exact_transmittance(scene, scene.lights[query.light], query.point);
        answers[q] = {r.rgb, r.flags};
      });
}

}  // namespace dv
