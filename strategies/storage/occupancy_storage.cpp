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
#include "strategies/storage/basis_storage.h"
#include "strategies/storage/occupancy_device.h"

namespace dv {

namespace {

class OccupancyStorage final : public BasisStorage<OccupancyStorage> {
 public:
  explicit OccupancyStorage(const StrategyParams& p)
      : BasisStorage(p, "dsm occupancy texels", "dsm_occupancy_write",
                     "folded into slice bits and slab sums, not stored"),
        slices_(p.integer("slices")),
        slabs_(p.integer("slabs")) {}
  std::string name() const override { return "occupancy"; }
  int stride() const { return occupancy_stride(slices_, slabs_); }
  auto sink() const { return OccupancySink{nullptr, slices_, slabs_}; }
  DsmReader reader() const override {
    return DsmReader(OccupancyReader{data_.const_view(), slices_, slabs_});
  }

 private:
  int slices_;
  int slabs_;
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
