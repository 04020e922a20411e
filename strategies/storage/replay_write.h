// The launches of a storage's write pass over a node replay (engine/dsm/node_replay.h): a kernel
// that replays every kept texel, then one that walks the lost ones again (persistent threads over
// the first pass's list of them, which the host never reads: with none lost its threads return at
// once); with an inactive replay, one kernel that walks every texel. The storage writes its pass
// as a template on kWalk whose body calls replay.generate<kWalk> and runs it through
// run_replay_write. Include only from files compiled by nvcc when CUDA is on.
#pragma once

#include <cstdint>

#include "cuda/execute.h"
#include "engine/dsm/node_replay.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

// body(thread, t) for the texels of one kind (t the generator thread's texel): kWalk false, the
// kept texels of an active replay; kWalk true, its lost texels, or every texel when the replay is
// inactive.
template <bool kWalk, class Body>
void for_replay_texels(const DsmGenerationContext& c, const NodeReplay& replay, const char* kernel,
                       Body body) {
  const DsmGenerator g = c.generator;
  const NodeReplay r = replay;
  if (!kWalk || !replay.active()) {
    parallel_for(
        c.backend, kernel, g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
          DsmTexel t;
          if (!g.texel_of_thread(i, t)) return;
          if (!kWalk && r.is_lost(t)) return;
          body(i, t);
        });
    return;
  }
  parallel_for_resident(
      c.backend, "dsm_replay_lost_walk", DV_KERNEL_LAMBDA(int64_t i, int64_t threads) {
        const int64_t lost = int64_t(r.lost_count());
        for (int64_t k = i; k < lost; k += threads) {
          DsmTexel t;
          g.texel_of_thread(r.lost[k], t);
          body(int64_t(r.lost[k]), t);
        }
      });
}

// A write pass written as a template on kWalk, `pass` being [&]<bool kWalk>() { ... }: the kept
// texels replayed when the replay is active (kWalk false), then the rest walked (kWalk true).
template <class Pass>
void run_replay_write(const NodeReplay& replay, Pass pass) {
  if (replay.active()) pass.template operator()<false>();
  pass.template operator()<true>();
}

}  // namespace dv
