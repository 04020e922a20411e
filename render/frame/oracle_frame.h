// The exact oracle's camera pass, deferred: the same answers to the bit as one pass in which each
// pixel's thread traces the shadow rays of its own samples, in a shape the GPU runs far better.
// In the one pass a warp holds 32 pixels whose walks differ (one crosses no volume, its
// neighbour takes a hundred samples, each with an exact shadow ray through the volume), so most
// lanes idle while the longest walk runs, and the walk, the shading and the oracle share one
// register budget. Deferred, the pass runs three cheap walks around one pass of shadow queries
// (render/frame/oracle_passes.h):
//   1. count:  each thread walks its pixel and counts the shadow queries it would ask (which
//              queries a walk asks depends on the scene and the camera, never on their answers:
//              shading only multiplies by them);
//   2. record: after a scan of the counts, each thread writes its queries (point, light) in the
//              order its walk asks them;
//   3. answer: one thread per query runs exact_transmittance, the queries sorted by light and,
//              within a light, by a cost estimate (the shadow ray's length in bricks that are
//              not empty), heaviest first, equal costs in pixel and sample order, so that a
//              warp's shadow rays leave one light and walk about as many volume cells;
//   4. replay: each thread walks its pixel again and reads its answers back in order.
// Every pixel sees the answers the direct pass computes, in the same order, so the image, the
// counters and the oracle flags are the same bits. Queries are kept in rounds of at most
// `queries_per_round` (64 bytes each); a frame that asks more runs rounds over consecutive
// ranges of the pass's threads. Both renderers (raster_render.h, reference_render.h) take it.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

namespace dv {

// Default bound of one round: 8 M queries, 512 MB of query and answer buffers.
inline constexpr int64_t kOracleQueriesPerRound = int64_t(1) << 23;

// How a frame with the exact oracle's shadows runs (other shadow methods ignore it): deferred
// (the default) or direct, one thread per pixel tracing its own shadow rays.
struct OracleFrameOptions {
  bool deferred = true;
  int64_t queries_per_round = kOracleQueriesPerRound;  // in [1, 2^30]
};

struct OracleFrameStats {
  int64_t queries = 0;       // shadow queries the frame asked (one per shaded sample and light)
  int64_t rounds = 0;        // rounds of record, answer and replay
  int64_t buffer_bytes = 0;  // query, answer and ordering buffers of one round, and the counts
  double count_ms = 0.0;     // walk 1 and the scan
  double record_ms = 0.0;    // walk 2 (all rounds)
  double answer_ms = 0.0;    // the exact queries, with their ordering by light (all rounds)
  double replay_ms = 0.0;    // walk 4 (all rounds)
  bool deferred() const { return rounds > 0; }  // a deferred pass ran (it takes >= 1 round)
  nlohmann::json stats() const;
};

}  // namespace dv
