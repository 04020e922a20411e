// Storage strategy `compact` (see compact_device.h): counting pass (which keeps the nodes for
// the packing pass, engine/dsm/node_replay.h), the two-level scan of the counts, packing pass.
// The faces go through these passes in sets whose replay scratch and per-texel records fit
// DsmGenerationContext::face_set_bytes, the scratch reused from set to set and each set's nodes
// packed into an array of their own, gathered into one at the end: the device never holds the
// scratch or the records of all faces at once (112 maps of 512^2: 1.9 GB of scratch in one set).
// Every set starts on a group of starts, so its starts are those of one generation of all faces
// less the nodes of the sets before, which are added once the set is packed: the maps are the
// same bits whatever the sets. Compiled by nvcc when CUDA is on.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "core/atomic.h"
#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "cuda/execute.h"
#include "cuda/scan.h"
#include "strategies/storage/compact_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/replay_write.h"

namespace dv {

namespace {

// Two blocks of 256 threads per SM (128 registers, parallel_for_bounded): the counting walk
// generates faster than at the occupancy calculator's 255 registers
// (results/perf/2026-12-06-register-budget).
void count_nodes(const DsmGenerationContext& c, NodeReplay replay, View<uint32_t> counts) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  parallel_for_bounded<2>(
      c.backend, "dsm_compact_count", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<KeepingSink<CountingNodeSink>> r =
            g.generate(t, eps, replay.sink<CountingNodeSink>(t));
        counts[t.index] = uint32_t(r.record.nodes);
        replay.keep(i, t, r);
      });
}

// Turns each group's counts into starts within the group and leaves the group's total in
// `group_starts` for the scan; the largest total above 2^32 - 1 (the starts within a group are
// 32-bit) goes to `largest`.
void start_within_groups(Backend backend, View<uint32_t> counts, View<int64_t> group_starts,
                         View<unsigned long long> largest) {
  parallel_for(
      backend, "dsm_compact_group_starts", group_starts.size, DV_KERNEL_LAMBDA(int64_t g) {
        const int64_t first = g * kCompactGroupTexels;
        const int64_t end = min_value(first + kCompactGroupTexels, counts.size);
        unsigned long long sum = 0;
        for (int64_t t = first; t < end; ++t) {
          const uint32_t n = counts[t];
          counts[t] = uint32_t(sum);
          sum += n;
        }
        group_starts[g] = int64_t(sum);
        if (sum > 0xffffffffull) atomic_max(largest.data, sum);
      });
}

template <bool kWalk>
void write_nodes(const DsmGenerationContext& c, NodeReplay replay, CompactStarts starts,
                 View<DsmNode> nodes) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  for_replay_texels<kWalk>(
      c, replay, "dsm_compact_write", DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        const int64_t begin = starts.start(t.index);
        const CompactSink sink{nodes.data + begin, starts.start(t.index + 1) - begin};
        records[t.index] = replay.generate<kWalk>(g, t, eps, sink).record;
      });
}

// Adds `base` to every group start of `group_starts`: a set's starts, packed into an array of
// its own, become those of the gathered array.
void add_to_starts(Backend backend, View<int64_t> group_starts, int64_t base) {
  parallel_for(
      backend, "dsm_compact_set_starts", group_starts.size,
      DV_KERNEL_LAMBDA(int64_t g) { group_starts[g] += base; });
}

// `from`'s nodes copied into `to` from node `first` on.
void gather_nodes(Backend backend, View<const DsmNode> from, View<DsmNode> to, int64_t first) {
  parallel_for(
      backend, "dsm_compact_gather", from.size,
      DV_KERNEL_LAMBDA(int64_t i) { to[first + i] = from[i]; });
}

// Faces in a set, for faces of `face_texels` texels and a set's scratch and records within
// `bytes`: as many as fit (at least one), in steps of faces that end on a group of starts.
int64_t faces_per_set(int64_t face_texels, int64_t bytes) {
  const int64_t face_bytes = face_texels * (kReplayBytesPerTexel + int64_t(sizeof(DsmTexelRecord)));
  const int64_t step = kCompactGroupTexels / std::gcd(face_texels, kCompactGroupTexels);
  return std::max<int64_t>(bytes / face_bytes / step, 1) * step;
}

// The generator of g's faces [first, first + count): the per-face views start at face `first`;
// texel indices (the faces' offsets) stay g's.
DsmGenerator face_set(const DsmGenerator& g, int64_t first, int64_t count) {
  DsmGenerator set = g;
  set.faces = {g.faces.data + first, count};
  set.lists = {g.lists.data + first, count};
  set.ray_media = {g.ray_media.data + first, count};
  if (g.mask_words > 0)
    set.object_masks = {g.object_masks.data + first * g.mask_words, count * g.mask_words};
  return set;
}

class CompactStorage final : public DsmStorage {
 public:
  std::string name() const override { return "compact"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }

  void generate(const DsmGenerationContext& c) override {
    const int64_t texels = c.generator.texel_count();
    const Memory memory = memory_of(c.backend);
    ensure_buffer(local_starts_, memory, texels + 1, "dsm compact starts within groups");
    ensure_buffer(group_starts_, memory, compact_groups(texels), "dsm compact group starts");
    ensure_buffer(largest_group_, memory, 1, "dsm compact largest group");
    // Face i's texels start at i * face_texels (light_faces.h).
    const int64_t faces = c.generator.faces.size;
    const int64_t face_texels = int64_t(c.generator.resolution) * c.generator.resolution;
    const int64_t per_set = faces_per_set(face_texels, c.face_set_bytes);
    sets_ = std::max<int64_t>((faces + per_set - 1) / per_set, 1);
    if (sets_ > 1) nodes_ = Buffer<DsmNode>();  // replaced by the sets' nodes, not held beside
    std::vector<Buffer<DsmNode>> parts;         // each set's nodes when there are several
    int64_t nodes = 0;                          // in the sets so far
    for (int64_t set = 0; set < sets_; ++set) {
      const int64_t first = set * per_set;
      const DsmGenerator g = face_set(c.generator, first, std::min(per_set, faces - first));
      const DsmGenerationContext s{
          c.backend, g, c.eps, c.records, c.passes, c.face_set_bytes, first * face_texels};
      Buffer<DsmNode>& out = sets_ == 1 ? nodes_ : parts.emplace_back();
      const int64_t set_nodes = generate_set(s, set == 0, out);
      if (nodes > 0) add_to_starts(c.backend, set_groups(s), nodes);
      nodes += set_nodes;
    }
    scratch_.end();
    if (sets_ == 1) return;
    ensure_buffer(nodes_, memory, nodes, "dsm compact nodes");
    timed_pass(c, "gather", [&] {
      int64_t first = 0;
      for (Buffer<DsmNode>& part : parts) {
        gather_nodes(c.backend, part.const_view(), nodes_.view(), first);
        first += part.size();
        part = Buffer<DsmNode>();
      }
    });
  }

  DsmReader reader() const override {
    return DsmReader(CompactReader{starts(), nodes_.const_view()});
  }
  int64_t bytes_allocated() const override {
    return group_starts_.bytes() + local_starts_.bytes() + nodes_.bytes();
  }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  DsmHostNodes host_nodes() const override {
    const std::vector<int64_t> groups = group_starts_.to_vector();
    const std::vector<uint32_t> local = local_starts_.to_vector();
    const CompactStarts host{{groups.data(), int64_t(groups.size())},
                             {local.data(), int64_t(local.size())}};
    std::vector<int64_t> offsets(local.size());
    for (size_t t = 0; t < offsets.size(); ++t) offsets[t] = host.start(int64_t(t));
    return {offsets, nodes_.to_vector()};
  }
  nlohmann::json own_figures() const override {
    nlohmann::json j = scratch_.figures();
    j["face_sets"] = sets_;
    return j;
  }

 private:
  CompactStarts starts() const { return {group_starts_.const_view(), local_starts_.const_view()}; }

  // The group starts of s's texels, and the group where the next set starts (which ends s's last
  // texel): as a set's texels start on a group, its groups are its own.
  View<int64_t> set_groups(const DsmGenerationContext& s) const {
    const int64_t first = s.first_texel / kCompactGroupTexels;
    const int64_t end = (s.first_texel + s.generator.texel_count()) / kCompactGroupTexels + 1;
    return {group_starts_.data() + first, end - first};
  }

  // Counts, scans and packs the set of faces of s (the first of the generation or not) into
  // `out`, with starts from the set's first node; returns its nodes.
  int64_t generate_set(const DsmGenerationContext& s, bool first_set, Buffer<DsmNode>& out) {
    const int64_t texels = s.generator.texel_count();
    timed_pass(s, "count", [&] {
      if (first_set) local_starts_.fill_zero();
      count_nodes(s, first_set ? scratch_.begin(s) : scratch_.next(s), local_starts_.view());
    });
    // The counts of the set and of the texel after it (zero: the next set's first, counted
    // later, or the end of all texels), whose start the scan makes the set's end.
    const View<uint32_t> counts{local_starts_.data() + s.first_texel, texels + 1};
    int64_t total = 0;
    timed_pass(s, "scan", [&] {
      largest_group_.fill_zero();
      start_within_groups(s.backend, counts, set_groups(s), largest_group_.view());
      total = exclusive_scan_in_place(s.backend, set_groups(s));
    });
    const unsigned long long largest = largest_group_.to_vector()[0];
    if (largest > 0) {
      scratch_.end();
      throw Error("dsm storage 'compact': " + std::to_string(largest) + " nodes in one group of " +
                  std::to_string(kCompactGroupTexels) +
                  " texels, more than its 32-bit starts hold (4294967295)");
    }
    ensure_buffer(out, memory_of(s.backend), total, "dsm compact nodes");
    s.texel_records();  // sums (and keeps) the set before's records here, outside the passes
    timed_pass(s, "write", [&] {
      const NodeReplay replay = scratch_.replay();
      run_replay_write(replay,
                       [&]<bool kWalk>() { write_nodes<kWalk>(s, replay, starts(), out.view()); });
    });
    return total;
  }

  Buffer<int64_t> group_starts_;
  Buffer<uint32_t> local_starts_;
  Buffer<unsigned long long> largest_group_;
  Buffer<DsmNode> nodes_;
  NodeReplayScratch scratch_;
  int64_t sets_ = 0;  // sets of faces of the last generation
};

}  // namespace

void register_compact_storage(Registry<DsmStorage>& registry) {
  registry.add("compact",
               "ours: count, scan, pack into one exact-size array; zero waste, binary search", {},
               [](const StrategyParams&) { return std::make_unique<CompactStorage>(); });
}

}  // namespace dv
