// The deferred oracle pass's machinery (see oracle_frame.h): the three walk sources, the rounds
// and the pass of exact shadow queries, driven for either renderer by a callback that launches
// its walk over a range of its threads with a given source. Included only by nvcc-compiled files.
#pragma once

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "cuda/pass_timer.h"
#include "cuda/scan.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"
#include "render/frame/oracle_frame.h"
#include "strategies/shadow/shadow_device.h"

namespace dv {

struct OracleQuery {
  dvec3 point;
  int32_t light;
};

struct OracleAnswer {
  dvec3 rgb;
  uint32_t flags;
};

struct OracleQueryCursor {
  uint32_t flags = 0;  // the oracle flags of the answers read (the replay's)
  int64_t next = 0;    // the thread's next query: a count, or an index into the round's buffers
};

// Walk 1: counts the queries of each thread.
struct OracleQueryCounter {
  View<int64_t> counts;
  using Cursor = OracleQueryCursor;
  static constexpr bool kWritesPixels = false;
  DV_HD dvec3 transmittance_rgb(Cursor& c, const ShadowReceiver&, int) const {
    ++c.next;
    return dvec3(1.0);
  }
  DV_HD void finish(const Cursor& c, int64_t thread) const { counts[thread] = c.next; }
};

// Walk 2: writes each thread's queries from its start in the round's buffer.
struct OracleQueryRecorder {
  View<const int64_t> starts;  // the scanned counts, over all threads
  int64_t round_start;         // starts[] of the round's first thread
  View<OracleQuery> queries;
  using Cursor = OracleQueryCursor;
  static constexpr bool kWritesPixels = false;
  DV_HD Cursor cursor_for(int64_t thread) const { return {0u, starts[thread] - round_start}; }
  DV_HD dvec3 transmittance_rgb(Cursor& c, const ShadowReceiver& r, int light) const {
    queries[c.next++] = {r.point, int32_t(light)};
    return dvec3(1.0);
  }
};

// Walk 4: reads the answers back in the order walk 2 wrote the queries.
struct OracleAnswerReader {
  View<const int64_t> starts;
  int64_t round_start;
  View<const OracleAnswer> answers;
  using Cursor = OracleQueryCursor;
  DV_HD Cursor cursor_for(int64_t thread) const { return {0u, starts[thread] - round_start}; }
  DV_HD dvec3 transmittance_rgb(Cursor& c, const ShadowReceiver&, int) const {
    const OracleAnswer& a = answers[c.next++];
    c.flags |= a.flags;
    return a.rgb;
  }
};

// Consecutive thread ranges [first, end) whose queries fit `per_round` each, from the scanned
// counts; boundaries at multiples of 32 (a range of 32 threads that alone asks more is a round
// of its own), so that a round's warps are those of a launch of all threads.
std::vector<std::pair<int64_t, int64_t>> plan_oracle_rounds(const std::vector<int64_t>& starts,
                                                            int64_t threads, int64_t per_round);

// The exact answers to queries[0, n) (pass 3), taken in the order of (light, cost estimate),
// heaviest first, equal keys in pixel and sample order.
void answer_oracle_queries(Backend backend, const SceneView& scene, View<const OracleQuery> queries,
                           View<OracleAnswer> answers, int64_t n);

// The deferred pass over `threads` walk threads: launch(name, first, count, source) runs the
// renderer's walk over threads [first, first + count) with `source`.
template <class LaunchWalk>
OracleFrameStats run_deferred_oracle(Backend backend, const SceneView& scene, int64_t threads,
                                     int64_t queries_per_round, LaunchWalk&& launch) {
  if (queries_per_round < 1 || queries_per_round > (int64_t(1) << 30))
    throw Error("oracle frame: queries per round must be in [1, 2^30], not " +
                std::to_string(queries_per_round));
  const Memory memory = memory_of(backend);
  OracleFrameStats stats;

  PassTimer count_timer(backend);
  Buffer<int64_t> starts(memory, threads + 1, "oracle query starts");
  starts.fill_zero();
  launch("oracle_count_walk", int64_t(0), threads, OracleQueryCounter{starts.view()});
  stats.queries = exclusive_scan_in_place(backend, starts.view());
  stats.count_ms = count_timer.stop();

  std::vector<std::pair<int64_t, int64_t>> rounds{{0, threads}};
  std::vector<int64_t> host_starts{0};  // of the rounds' first threads; all, with several rounds
  int64_t most = stats.queries;
  if (stats.queries > queries_per_round) {
    host_starts = starts.to_vector();
    rounds = plan_oracle_rounds(host_starts, threads, queries_per_round);
    most = 0;
    for (const auto& [first, end] : rounds)
      most = std::max(most, host_starts[size_t(end)] - host_starts[size_t(first)]);
  }
  stats.rounds = int64_t(rounds.size());
  Buffer<OracleQuery> queries(memory, most, "oracle queries");
  Buffer<OracleAnswer> answers(memory, most, "oracle answers");
  stats.buffer_bytes = int64_t(starts.bytes() + queries.bytes() + answers.bytes()) +
                       12 * most;  // the answer pass's keys and order

  const View<const int64_t> scanned = starts.const_view();
  for (const auto& [first, end] : rounds) {
    const int64_t round_start = host_starts[size_t(first)];
    const int64_t n = rounds.size() > 1 ? host_starts[size_t(end)] - round_start : stats.queries;

    PassTimer record_timer(backend);
    launch("oracle_record_walk", first, end - first,
           OracleQueryRecorder{scanned, round_start, queries.view()});
    stats.record_ms += record_timer.stop();

    PassTimer answer_timer(backend);
    answer_oracle_queries(backend, scene, queries.const_view(), answers.view(), n);
    stats.answer_ms += answer_timer.stop();

    PassTimer replay_timer(backend);
    launch("oracle_replay_walk", first, end - first,
           OracleAnswerReader{scanned, round_start, answers.const_view()});
    stats.replay_ms += replay_timer.stop();
  }
  return stats;
}

// A renderer's frame with shadow source `s`: deferred when `s` is the exact oracle and `options`
// ask for it, then true with its figures in `stats`; false for every other source, which the
// renderer shades in its one pass.
template <class Source, class LaunchWalk>
bool run_if_deferred_oracle(Backend backend, const Source& s, int64_t threads,
                            const OracleFrameOptions& options, OracleFrameStats& stats,
                            LaunchWalk&& launch) {
  if constexpr (std::is_same_v<Source, ReferenceShadowSource>) {
    if (!options.deferred) return false;
    stats = run_deferred_oracle(backend, s.scene, threads, options.queries_per_round, launch);
    return true;
  } else {
    return false;
  }
}

}  // namespace dv
