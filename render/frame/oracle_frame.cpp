// The deferred oracle pass's rounds and its pass of exact shadow queries (see oracle_passes.h).
#include <algorithm>

#include "cuda/sort.h"
#include "engine/oracle/transmittance.h"
#include "render/frame/oracle_passes.h"

namespace dv {

namespace {

int key_bits_for(int64_t lights) {
  int bits = 1;
  while ((int64_t(1) << bits) < lights) ++bits;
  return bits;
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

void answer_oracle_queries(Backend backend, const SceneView& scene, View<const OracleQuery> queries,
                           View<OracleAnswer> answers, int64_t n) {
  if (n == 0) return;
  const Memory memory = memory_of(backend);
  const int64_t lights = scene.lights.size;
  Buffer<uint32_t> keys(memory, lights > 1 ? n : 0, "oracle query lights");
  Buffer<int32_t> index(memory, lights > 1 ? n : 0, "oracle query index");
  Buffer<int32_t> by_light(memory, lights > 1 ? n : 0, "oracle queries by light");
  const View<const int32_t> order = by_light.const_view();
  if (lights > 1) {
    const View<uint32_t> k = keys.view();
    const View<int32_t> i = index.view();
    parallel_for(
        backend, "oracle_query_keys", n, DV_KERNEL_LAMBDA(int64_t q) {
          k[q] = uint32_t(queries[q].light);
          i[q] = int32_t(q);
        });
    sort_by_key_descending_queued(backend, keys.const_view(), index.const_view(), by_light.view(),
                                  key_bits_for(lights));
  }
  parallel_for(
      backend, "oracle_answers", n, DV_KERNEL_LAMBDA(int64_t j) {
        const int64_t q = order.empty() ? j : int64_t(order[j]);
        const OracleQuery query = queries[q];
        const OracleResult r = exact_transmittance(scene, scene.lights[query.light], query.point);
        answers[q] = {r.rgb, r.flags};
      });
}

}  // namespace dv
