// Storage strategy `texture3d` (see texture3d_device.h). Parameters (table at the
// registration): layers, sizing (strategies/storage/pool_sizing.h; counted gives the atlas as many
// layers as the deepest texel needs, at most `layers`; thesis always `layers`). Overflow policy: a
// texel whose compressed function needs more nodes than layers is compressed again with eps doubled
// (from at least 1/1024) until it fits, which keeps the whole function, now within the larger
// bound, instead of cutting it off; with eps = 1 a function needs one node, so every texel fits.
// The walk's samples stay those of the asked eps. Such texels count as overflowed, with the error
// bound they reached. Counted sizing costs one counting pass for the first maps of a size only:
// later generations write into the previous depth, measure the deepest texel in the same walk and
// write again only when it grew (the atlas ends as deep as the deepest texel, exactly as after a
// counting pass). Compiled by nvcc when CUDA is on.
#include <algorithm>
#include <memory>

#include "core/atomic.h"
#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/pool_sizing.h"
#include "strategies/storage/texture3d_device.h"

namespace dv {

namespace {

// Writes every texel into an atlas of `layers` layers. `final` (the atlas has the strategy's
// limit): a texel that does not fit is recompressed with a doubled eps until it does; otherwise
// (a first guess of the counted size) it is left overflowed, to be written again into a deeper
// atlas. `deepest` (if not null) receives the most nodes any texel needs at eps.
void write_layers(const DsmGenerationContext& c, int layers, bool final, View<DsmNode> atlas,
                  View<int32_t> counts, int32_t* deepest) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  const int64_t texels = g.texel_count();
  parallel_for(
      c.backend, "dsm_texture3d_write", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const Texture3dSink empty{atlas.data + t.index, texels, layers};
        DsmTexelResult<Texture3dSink> r = g.generate(t, eps, empty);
        if (deepest) atomic_max_combined(deepest, r.record.nodes);
        float e = eps;
        bool recompressed = false;
        while (final && (r.record.flags & kDsmStorageOverflow) && e < 1.0f) {
          e = min_value(1.0f, max_value(2.0f * e, 1.0f / 1024.0f));
          r = g.generate(t, e, empty, eps);
          recompressed = true;
        }
        if (recompressed) r.record.flags |= kDsmRecompressed;
        counts[t.index] = r.sink.count;
        records[t.index] = r.record;
      });
}

// The first `count` nodes of `from` copied into `to`, on the backend.
void copy_nodes(Backend backend, View<const DsmNode> from, View<DsmNode> to, int64_t count) {
  parallel_for(
      backend, "dsm_texture3d_shrink", count, DV_KERNEL_LAMBDA(int64_t i) { to[i] = from[i]; });
}

class Texture3dStorage final : public DsmStorage {
 public:
  explicit Texture3dStorage(const StrategyParams& p)
      : params_(p), layers_(p.integer("layers")), sizing_(read_pool_sizing(p)) {}
  std::string name() const override { return "texture3d"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const int64_t texels = c.generator.texel_count();
    const Memory memory = memory_of(c.backend);
    ensure_buffer(counts_, memory, texels, "dsm texture3d layer counts");
    if (sizing_ == PoolSizing::thesis) {
      texels_ = texels;
      atlas_layers_ = layers_;
      ensure_buffer(atlas_, memory, texels * atlas_layers_, "dsm texture3d atlas");
      timed_pass(c, "write",
                 [&] { write_layers(c, layers_, true, atlas_.view(), counts_.view(), nullptr); });
      return;
    }
    // Counted: the first generation of a map size counts first; later ones write into the
    // previous generation's depth while measuring the deepest texel, and then write again
    // deeper only if some texel needs more, or keep the layers in use if fewer suffice.
    if (texels != texels_ || atlas_layers_ == 0) {
      const int32_t deepest = count_nodes_per_group(c, {NodeCountGroups::all, true}, 1)[0];
      atlas_layers_ = std::max(1, std::min(layers_, deepest));
    }
    texels_ = texels;
    ensure_buffer(deepest_, memory, 1, "dsm texture3d deepest texel");
    ensure_buffer(atlas_, memory, texels * atlas_layers_, "dsm texture3d atlas");
    timed_pass(c, "write", [&] {
      deepest_.fill_zero();
      write_layers(c, atlas_layers_, atlas_layers_ == layers_, atlas_.view(), counts_.view(),
                   deepest_.data());
    });
    const int needed = std::max(1, std::min(layers_, deepest_.to_vector()[0]));
    if (needed > atlas_layers_) {
      atlas_layers_ = needed;
      ensure_buffer(atlas_, memory, texels * atlas_layers_, "dsm texture3d atlas");
      timed_pass(c, "rewrite", [&] {
        write_layers(c, atlas_layers_, atlas_layers_ == layers_, atlas_.view(), counts_.view(),
                     nullptr);
      });
    } else if (needed < atlas_layers_) {
      // Layer k of every texel is one slab, so the first `needed` layers are a prefix.
      atlas_layers_ = needed;
      Buffer<DsmNode> smaller(memory, texels * atlas_layers_, "dsm texture3d atlas");
      timed_pass(c, "shrink", [&] {
        copy_nodes(c.backend, atlas_.const_view(), smaller.view(), smaller.size());
      });
      atlas_ = std::move(smaller);
    }
  }

  DsmReader reader() const override {
    return DsmReader(Texture3dReader{atlas_.const_view(), counts_.const_view(), texels_});
  }
  int64_t bytes_allocated() const override { return atlas_.bytes() + counts_.bytes(); }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  nlohmann::json own_figures() const override {
    return {{"atlas_bytes", atlas_.bytes()}, {"layers", atlas_layers_}};
  }

 private:
  StrategyParams params_;
  int layers_;
  PoolSizing sizing_;
  int atlas_layers_ = 0;
  int64_t texels_ = 0;
  Buffer<DsmNode> atlas_;
  Buffer<int32_t> counts_;
  Buffer<int32_t> deepest_;  // counted sizing: the most nodes a texel needed in the last write
};

}  // namespace

void register_texture3d_storage(Registry<DsmStorage>& registry) {
  registry.add("texture3d",
               "Knecht 2011 4.2.1: one 3D atlas, fixed layers per texel, coherent binary search",
               {integer_param("layers", 64, 1, 4096,
                              "most nodes per texel (the thesis's maximum 64); deeper texels are "
                              "compressed again with eps doubled until they fit"),
                pool_sizing_param()},
               [](const StrategyParams& p) { return std::make_unique<Texture3dStorage>(p); });
}

}  // namespace dv
