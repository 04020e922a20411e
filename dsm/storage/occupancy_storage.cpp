// Storage strategy `occupancy`: occupancy maps after Sintorn & Assarsson 2009 ("Hair self
// shadowing and transparency depth ordering using occupancy maps", I3D): per texel a bit per
// slice of its own depth range and a slab map of optical depth (occupancy_device.h: the
// lookup, the slice rule, what leaks). A DSM storage like moments and fourier: its input is the
// DSM generation walk's per-texel visibility function, and faces, clusters, receiver bias and
// filtering are the dsm method's. The paper builds its bits and slab sums by rasterising hair
// fragments into slices; here the same record is filled from the texel's nodes, so every
// caster kind (surfaces, media) reaches it. `transmittance-slicemap` is the other reading of
// the idea: the voxelizer's bit grid over the light frustum, one alpha for all surfaces.
// Passes: `range` (first and last node depth), `write` (the bits and slab sums). Bytes per
// texel: 4 * (3 + K + S / 32): 36 at the defaults (S = 64, K = 4). Parameters: slices (S: 32,
// 64 or 128, default 64), slabs (K: 1, 2, 4 or 8, default 4). The answer does not respect eps:
// one slice's optical depth per step remains. Compiled by nvcc when CUDA is on.
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "dsm/storage/basis_texel_write.h"
#include "dsm/storage/dsm_storage.h"
#include "dsm/storage/occupancy_device.h"

namespace dv {

namespace {

class OccupancyStorage final : public DsmStorage {
 public:
  explicit OccupancyStorage(const StrategyParams& p)
      : params_(p), slices_(p.integer("slices")), slabs_(p.integer("slabs")) {}
  std::string name() const override { return "occupancy"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const int stride = occupancy_stride(slices_, slabs_);
    ensure_buffer(data_, memory_of(c.backend), c.generator.texel_count() * stride,
                  "dsm occupancy texels");
    generate_basis_texels(c, scratch_, "dsm_occupancy_write",
                          OccupancySink{nullptr, slices_, slabs_}, stride, data_.view());
  }

  DsmReader reader() const override {
    DsmReader r;
    r.kind = DsmReaderKind::occupancy;
    r.occupancy = {data_.const_view(), slices_, slabs_};
    return r;
  }
  int64_t bytes_allocated() const override { return data_.bytes(); }
  // Nodes are folded into slice bits and slab sums, not stored; its error is measured against
  // the oracle, not bounded by eps.
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return 0; }
  nlohmann::json own_figures() const override {
    nlohmann::json figures = {
        {"bytes_per_texel", int64_t(sizeof(float)) * occupancy_stride(slices_, slabs_)},
        {"nodes", "folded into slice bits and slab sums, not stored"}};
    figures.update(scratch_.figures());
    return figures;
  }

 private:
  StrategyParams params_;
  int slices_;
  int slabs_;
  Buffer<float> data_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_occupancy_storage(Registry<DsmStorage>& registry) {
  registry.add(
      "occupancy",
      "Sintorn & Assarsson 2009 occupancy maps: a bit per slice of the texel's depth "
      "range and a slab map of optical depth",
      {integer_choice_param("slices", 64, {32, 64, 128}, "bits per texel over its own depth range"),
       integer_choice_param("slabs", 4, {1, 2, 4, 8},
                            "sums of optical depth per texel, each over slices / slabs")},
      [](const StrategyParams& p) { return std::make_unique<OccupancyStorage>(p); });
}

}  // namespace dv
