// Storage strategy `texture3d` (see texture3d_layout.h). Parameters: layers (default 64, the
// thesis's maximum), sizing = counted | thesis (dsm/storage/pool_sizing.h; counted, the
// default, gives the atlas as many layers as the deepest texel needs, at most `layers`; thesis
// always `layers`). Overflow policy: a texel whose compressed function needs more nodes than
// layers is compressed again with eps doubled (from at least 1/1024) until it fits, which
// keeps the whole function, now within the larger bound, instead of cutting it off; with
// eps = 1 a function needs one node, so every texel fits. The walk's samples stay those of
// the asked eps. Such texels count as overflowed, with
// the error bound they reached. Compiled by nvcc when CUDA is on.
#include <algorithm>
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "dsm/storage/dsm_storage.h"
#include "dsm/storage/pool_sizing.h"
#include "dsm/storage/texture3d_device.h"

namespace dv {

namespace {

void write_layers(const DsmGenerationContext& c, int layers, View<DsmNode> atlas,
                  View<int32_t> counts) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const View<DsmTexelRecord> records = c.records;
  const int64_t texels = g.texel_count();
  parallel_for(
      c.backend, "dsm_texture3d_write", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const Texture3dSink empty{atlas.data + t.index, texels, layers};
        DsmTexelResult<Texture3dSink> r = g.generate(t, eps, empty);
        float e = eps;
        bool recompressed = false;
        while ((r.record.flags & kDsmStorageOverflow) && e < 1.0f) {
          e = min_value(1.0f, max_value(2.0f * e, 1.0f / 1024.0f));
          r = g.generate(t, e, empty, eps);
          recompressed = true;
        }
        if (recompressed) r.record.flags |= kDsmRecompressed;
        counts[t.index] = r.sink.count;
        records[t.index] = r.record;
      });
}

class Texture3dStorage final : public DsmStorage {
 public:
  explicit Texture3dStorage(const StrategyParams& p)
      : layers_(p.integer("layers", 64)), sizing_(read_pool_sizing(p)) {
    if (layers_ < 1 || layers_ > 4096)
      throw InputError("texture3d layers", "must lie in [1, 4096]");
  }
  std::string name() const override { return "texture3d"; }
  nlohmann::json params() const override {
    return {{"layers", layers_}, {"sizing", to_string(sizing_)}};
  }

  void generate(const DsmGenerationContext& c) override {
    const int64_t texels = c.generator.texel_count();
    texels_ = texels;
    atlas_layers_ = layers_;
    if (sizing_ == PoolSizing::counted) {
      const int32_t deepest = count_nodes_per_group(c, {NodeCountGroups::all, true}, 1)[0];
      atlas_layers_ = std::max(1, std::min(layers_, deepest));
    }
    ensure_buffer(atlas_, memory_of(c.backend), texels * atlas_layers_, "dsm texture3d atlas");
    ensure_buffer(counts_, memory_of(c.backend), texels, "dsm texture3d layer counts");
    timed_pass(c, "write", [&] { write_layers(c, atlas_layers_, atlas_.view(), counts_.view()); });
  }

  DsmReader reader() const override {
    DsmReader r;
    r.kind = DsmReaderKind::texture3d;
    r.texture3d = {atlas_.const_view(), counts_.const_view(), texels_};
    return r;
  }
  int64_t bytes_allocated() const override { return atlas_.bytes() + counts_.bytes(); }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  nlohmann::json own_figures() const override {
    return {{"atlas_bytes", atlas_.bytes()}, {"layers", atlas_layers_}};
  }

 private:
  int layers_;
  PoolSizing sizing_;
  int atlas_layers_ = 0;
  int64_t texels_ = 0;
  Buffer<DsmNode> atlas_;
  Buffer<int32_t> counts_;
};

}  // namespace

void register_texture3d_storage(Registry<DsmStorage>& registry) {
  registry.add("texture3d",
               "Knecht 2011 4.2.1: one 3D atlas, fixed layers per texel, coherent binary search "
               "(params: layers, sizing=counted|thesis)",
               [](const StrategyParams& p) { return std::make_unique<Texture3dStorage>(p); });
}

}  // namespace dv
