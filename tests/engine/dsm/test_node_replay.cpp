// The node replay of the two-pass storages (engine/dsm/node_replay.h): a first pass that keeps each
// texel's nodes, then a replay into a sink, gives exactly the nodes and records of a second walk
// on the same backend, with the stripes roomy, short or empty (texels lost and walked again),
// texels deeper than one chunk (linked chunks), sinks too small for the function (overflow
// records), one first pass replayed several times; and a replay that is not active walks. On the
// CPU threads and on CUDA (skipped without a GPU).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "engine/dsm/node_replay.h"
#include "strategies/storage/compact_device.h"
#include "strategies/storage/replay_write.h"
#include "tests/engine/dsm/dsm_test_support.h"

namespace dv {
namespace {

// Nodes a texel's output slot holds (a deeper function overflows it, the same way in both runs).
constexpr int kSlotNodes = 64;
// Slot sizes the outputs are written with: overflowing first.
const std::vector<int> kCapacities = {1, 3, kSlotNodes};

// A spot light above a stack of 12 translucent quads, each wider than the one above: up to 24
// nodes (twin nodes at every surface) on the texels inside all of them, six chunks, fewer
// towards the rim.
Scene quad_stack_scene() {
  test::SceneBuilder b;
  for (int i = 0; i < 12; ++i) {
    TriangleMesh q = make_quad(0.5 + 0.3 * i);
    for (dvec3& v : q.positions) v.y = double(i) * 0.01;
    b.add(std::move(q), 0.1);
  }
  b.spot(dvec3(0.0, 10.0, 0.0), dvec3(0.0, -1.0, 0.0), 10.0);
  validate_scene(b.scene);
  return b.scene;
}

struct TexelOutputs {
  std::vector<DsmNode> nodes;  // kSlotNodes per texel
  std::vector<DsmTexelRecord> records;
  bool operator==(const TexelOutputs& o) const {
    if (records.size() != o.records.size() || nodes.size() != o.nodes.size()) return false;
    for (size_t i = 0; i < records.size(); ++i) {
      const DsmTexelRecord& a = records[i];
      const DsmTexelRecord& b = o.records[i];
      if (a.nodes != b.nodes || a.stored != b.stored || a.error != b.error || a.flags != b.flags)
        return false;
      for (int k = 0; k < a.stored; ++k) {
        const DsmNode& p = nodes[i * kSlotNodes + k];
        const DsmNode& q = o.nodes[i * kSlotNodes + k];
        if (p.z != q.z || p.v != q.v) return false;
      }
    }
    return true;
  }
};

// The write pass's kernels (strategies/storage/replay_write.h) into slots of `capacity` nodes.
template <bool kWalk>
void write_texels(const DsmGenerationContext& c, NodeReplay replay, int capacity,
                  View<DsmNode> out) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  for_replay_texels<kWalk>(
      c, replay, "test_replay_write", DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        const CompactSink sink{out.data + t.index * kSlotNodes, capacity};
        records[t.index] = replay.generate<kWalk>(g, t, eps, sink).record;
      });
}

// Every texel of g into a slot of `capacity` nodes, as a storage's write pass does it: the kept
// texels replayed, the lost ones walked (every texel when the replay is inactive).
TexelOutputs write_texels(Backend backend, const DsmGenerator& generator, NodeReplay replay,
                          float eps, int capacity) {
  const int64_t texels = generator.texel_count();
  Buffer<DsmNode> nodes(memory_of(backend), texels * kSlotNodes, "test replay nodes");
  DsmRecords records;
  records.start(backend, texels, false);
  const DsmGenerationContext c{backend, generator, eps, records, nullptr};
  run_replay_write(replay,
                   [&]<bool kWalk>() { write_texels<kWalk>(c, replay, capacity, nodes.view()); });
  if (backend == Backend::cuda) device_synchronize("test_replay_write");
  records.finish();
  return {nodes.to_vector(), records.host()};
}

struct FirstPass {
  Buffer<DsmNode> nodes;
  Buffer<int32_t> next;
  Buffer<KeptTexel> kept;
  Buffer<int32_t> lost;
  Buffer<unsigned long long> counters;
  NodeReplay replay;
  std::vector<int32_t> counts;  // the first pass's node count of each texel
};

// The first pass over every texel of g with stripes of `share` further chunks.
void keep_texels(Backend backend, const DsmGenerator& generator, float eps, int32_t share,
                 FirstPass& f) {
  const Memory memory = memory_of(backend);
  const int64_t texels = generator.texel_count();
  const int64_t chunks = replay_chunks(texels, share);
  f.nodes = Buffer<DsmNode>(memory, chunks * kReplayChunkNodes, "test replay chunks");
  f.next = Buffer<int32_t>(memory, chunks, "test replay links");
  f.kept = Buffer<KeptTexel>(memory, texels, "test replay kept");
  f.lost = Buffer<int32_t>(memory, texels, "test replay lost");
  f.counters = Buffer<unsigned long long>(memory, kReplayCounters, "test replay counters");
  f.counters.fill_zero();
  Buffer<int32_t> counts(memory, texels, "test replay counts");
  f.replay = {f.nodes.view(), f.next.view(),     f.kept.view(),
              f.lost.view(),  f.counters.view(), share};
  const NodeReplay replay = f.replay;
  const View<int32_t> count_of = counts.view();
  const DsmGenerator g = generator;
  parallel_for(
      backend, "test_replay_keep", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<KeepingSink<CountingNodeSink>> r =
            g.generate(t, eps, replay.sink<CountingNodeSink>(t));
        count_of[t.index] = r.sink.inner.count;
        replay.keep(i, t, r);
      });
  if (backend == Backend::cuda) device_synchronize("test_replay_keep");
  f.counts = counts.to_vector();
}

struct ReplayCase {
  const char* scene;
  int res;
  float eps;
};

class NodeReplayCases : public ::testing::TestWithParam<std::tuple<ReplayCase, Backend>> {};

TEST_P(NodeReplayCases, ReplayGivesTheNodesAndRecordsOfASecondWalk) {
  const auto [c, backend] = GetParam();
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    GTEST_SKIP() << "the CUDA replay needs a GPU: " << why;
  const std::string name = c.scene;
  const Scene scene = name == "quad-stack" ? quad_stack_scene() : test::scene_file(name);
  const SceneData data(scene, memory_of(backend));
  const DsmGeneration generation(data, backend, {.resolution = c.res});
  const DsmGenerator& g = generation.generator();

  FirstPass probe;
  keep_texels(backend, g, c.eps, 0, probe);
  const ReplayClaims asked = replay_claims(probe.counters.to_vector());
  int64_t further = 0, deep = 0;
  for (const int32_t n : probe.counts) {
    const int64_t chunks = (n + kReplayChunkNodes - 1) / kReplayChunkNodes;
    further += chunks > 1 ? chunks - 1 : 0;
    deep += n > kReplayChunkNodes;
  }
  ASSERT_GT(deep, 0) << name << ": the case must have texels deeper than a chunk";
  EXPECT_EQ(asked.asked, further) << name;
  EXPECT_EQ(asked.walked, deep) << name << ": empty stripes keep no texel deeper than a chunk";
  // Roomy: every stripe as large as the busiest asked for (what NodeReplayScratch reserves).
  const int32_t roomy = int32_t(asked.largest_stripe);

  std::vector<TexelOutputs> walked;
  for (const int capacity : kCapacities) {
    walked.push_back(write_texels(backend, g, NodeReplay{}, c.eps, capacity));
    if (capacity == 1) {
      int64_t overflowed = 0;
      for (const DsmTexelRecord& r : walked.back().records)
        overflowed += (r.flags & kDsmStorageOverflow) != 0;
      ASSERT_GT(overflowed, 0) << name << ": one-node slots must overflow";
    }
  }
  for (const int32_t share : {roomy, roomy / 2, 0}) {
    FirstPass first;
    keep_texels(backend, g, c.eps, share, first);
    const ReplayClaims claims = replay_claims(first.counters.to_vector());
    EXPECT_EQ(claims.asked, further) << name;
    if (share == roomy)
      EXPECT_EQ(claims.walked, 0) << name << ": walked again with roomy stripes";
    else
      EXPECT_GT(claims.walked, 0) << name << ": walked again with short stripes";
    // One first pass replayed once per slot size, overflowing ones first: a replay reads only
    // what the first pass wrote (chunked writes again after a pool ran short).
    for (size_t k = 0; k < kCapacities.size(); ++k) {
      const TexelOutputs replayed = write_texels(backend, g, first.replay, c.eps, kCapacities[k]);
      EXPECT_TRUE(replayed == walked[k]) << name << " on " << to_string(backend) << ", slots of "
                                         << kCapacities[k] << ", stripes of " << share;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    ScenesAndBackends, NodeReplayCases,
    ::testing::Combine(::testing::Values(ReplayCase{"knecht-fig56.json", 64, 0.02f},
                                         ReplayCase{"ct-phantom.json", 48, 0.005f},
                                         ReplayCase{"quad-stack", 16, 0.0f}),
                       ::testing::Values(Backend::cpu, Backend::cuda)),
    [](const ::testing::TestParamInfo<NodeReplayCases::ParamType>& info) {
      std::string name = std::get<0>(info.param).scene;
      name = name.substr(0, name.find('.'));
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name + "_" + to_string(std::get<1>(info.param));
    });

}  // namespace
}  // namespace dv
