// The shared body of the storages that fold a texel's nodes into a fixed record of floats
// (moments, fourier, occupancy): one buffer of `stride` floats per texel, written by the basis
// passes (basis_texel_write.h: `range`, then `write` through the storage's sink), its bytes and
// figures, and no eps bound (their error is measured against the oracle). A storage of this
// kind derives BasisStorage<Itself> and gives its stride(), its sink() prototype, reader() and
// name(). Compiled where the deriving storage is (nvcc when CUDA is on).
#pragma once

#include <cstdint>

#include "cuda/ensure_buffer.h"
#include "strategies/storage/basis_texel_write.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

template <class Derived>
class BasisStorage : public DsmStorage {
 public:
  // texels_label names the buffer in memory errors, write_pass the write kernel in timings,
  // folded_into what becomes of the nodes (the `nodes` figure).
  BasisStorage(const StrategyParams& p, const char* texels_label, const char* write_pass,
               const char* folded_into)
      : params_(p),
        texels_label_(texels_label),
        write_pass_(write_pass),
        folded_into_(folded_into) {}

  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const Derived& self = static_cast<const Derived&>(*this);
    const int stride = self.stride();
    ensure_buffer(data_, memory_of(c.backend), c.generator.texel_count() * stride, texels_label_);
    generate_basis_texels(c, scratch_, write_pass_, self.sink(), stride, data_.view());
  }

  int64_t bytes_allocated() const override { return data_.bytes(); }
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return 0; }
  nlohmann::json own_figures() const override {
    const Derived& self = static_cast<const Derived&>(*this);
    nlohmann::json figures = {{"bytes_per_texel", int64_t(sizeof(float)) * self.stride()},
                              {"nodes", folded_into_}};
    figures.update(scratch_.figures());
    return figures;
  }

 protected:
  StrategyParams params_;
  Buffer<float> data_;

 private:
  const char* texels_label_;
  const char* write_pass_;
  const char* folded_into_;
  NodeReplayScratch scratch_;
};

}  // namespace dv
