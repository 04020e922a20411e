// Storage strategy `beer` (Unreal Engine 5's Beer shadow map, see beer_device.h): an entry and an
// exit node per texel, 16 bytes, lookups by Beer-Lambert interpolation between them. A storage
// strategy rather than a shadow method for avsm's reason (avsm_storage.cpp): only what a texel
// keeps changes, so walk, bias and filter are those of `dsm`. The walk samples constant media
// for the shared eps; the function reaches the sink exactly (compressor eps 0). One pass; a
// texel whose function has more than two nodes is flagged kDsmNodesMerged with the bound
// v_in - v_out. Compiled by nvcc when CUDA is on.
#include <memory>

#include "cuda/ensure_buffer.h"
#include "strategies/storage/beer_device.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

namespace {

void write_beer_texels(const DsmGenerationContext& c, View<BeerTexel> texels) {
  const DsmGenerator g = c.generator;
  const float sample_eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  parallel_for(
      c.backend, "dsm_beer_write", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<BeerSink> r = g.generate(t, 0.0f, BeerSink{}, sample_eps);
        texels[t.index] = r.sink.texel;
        DsmTexelRecord record = r.record;
        record.stored = r.sink.stored();
        if (record.nodes > record.stored) {
          record.error = min_value(record.error + r.sink.error_bound(), 1.0f);
          record.flags |= kDsmNodesMerged;
        }
        records[t.index] = record;
      });
}

class BeerStorage final : public DsmStorage {
 public:
  std::string name() const override { return "beer"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }

  void generate(const DsmGenerationContext& c) override {
    ensure_buffer(texels_, memory_of(c.backend), c.generator.texel_count(), "dsm beer texels");
    timed_pass(c, "write", [&] { write_beer_texels(c, texels_.view()); });
  }

  DsmReader reader() const override { return DsmReader(BeerReader{texels_.const_view()}); }
  int64_t bytes_allocated() const override { return texels_.bytes(); }
  // A fixed number of nodes: its error is measured against the oracle, not bounded by eps.
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  nlohmann::json own_figures() const override {
    return {{"bytes_per_texel", int64_t(sizeof(BeerTexel))}};
  }

 private:
  Buffer<BeerTexel> texels_;
};

}  // namespace

void register_beer_storage(Registry<DsmStorage>& registry) {
  registry.add("beer",
               "UE 5 Beer shadow map: entry and exit depth and transmittance per texel (16 bytes), "
               "Beer-Lambert interpolation between them; error unbounded",
               {}, [](const StrategyParams&) { return std::make_unique<BeerStorage>(); });
}

}  // namespace dv
