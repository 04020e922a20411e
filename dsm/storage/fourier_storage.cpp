// Storage strategy `fourier`: Fourier opacity maps (Jansen & Bavoil 2010, "Fourier Opacity
// Mapping", I3D): per texel K frequencies of the optical-depth density over the texel's
// normalised depth, the integral reconstructed in closed form (fourier_layout.h: ringing and
// clamping). A DSM storage, not a shadow method: its input is exactly the DSM generation walk's
// per-texel visibility function (the sink interface of dsm_storage.h), and faces, clusters,
// receiver bias and filtering are the dsm method's. Passes: `range` (first and last node
// depth), `write` (the nodes replayed, dsm/node_replay.h, and projected). Bytes per texel: 4 * (4 +
// 2K): 48 (K = 4), 80 (K = 8), 144 (K = 16). Parameter: frequencies (K). The answer does not
// respect eps: truncation error and ringing remain. Compiled by nvcc when CUDA is on.
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "dsm/storage/basis_texel_write.h"
#include "dsm/storage/dsm_storage.h"
#include "dsm/storage/fourier_device.h"

namespace dv {

namespace {

class FourierStorage final : public DsmStorage {
 public:
  explicit FourierStorage(const StrategyParams& p)
      : params_(p), frequencies_(p.integer("frequencies")) {}
  std::string name() const override { return "fourier"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const int stride = fourier_stride(frequencies_);
    ensure_buffer(data_, memory_of(c.backend), c.generator.texel_count() * stride,
                  "dsm fourier texels");
    generate_basis_texels(c, scratch_, "dsm_fourier_write", FourierSink{nullptr, frequencies_},
                          stride, data_.view());
  }

  DsmReader reader() const override {
    DsmReader r;
    r.kind = DsmReaderKind::fourier;
    r.fourier = {data_.const_view(), frequencies_};
    return r;
  }
  int64_t bytes_allocated() const override { return data_.bytes(); }
  // Nodes are folded into the coefficients, not stored.
  // Basis coefficients: its error is measured against the oracle, not bounded by eps.
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return 0; }
  nlohmann::json own_figures() const override {
    nlohmann::json figures = {
        {"bytes_per_texel", int64_t(sizeof(float)) * fourier_stride(frequencies_)},
        {"nodes", "folded into the coefficients, not stored"}};
    figures.update(scratch_.figures());
    return figures;
  }

 private:
  StrategyParams params_;
  int frequencies_;
  Buffer<float> data_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_fourier_storage(Registry<DsmStorage>& registry) {
  registry.add("fourier",
               "Jansen & Bavoil 2010 Fourier opacity maps: K frequencies of the optical-depth "
               "density per texel, ringing clamped",
               {integer_param("frequencies", 8, 1, kMaxFourierFrequencies,
                              "frequencies K per texel (4 (4 + 2K) bytes)")},
               [](const StrategyParams& p) { return std::make_unique<FourierStorage>(p); });
}

}  // namespace dv
