// Storage strategy `fourier`: Fourier opacity maps (Jansen & Bavoil 2010, "Fourier Opacity
// Mapping", I3D): per texel K frequencies of the optical-depth density over the texel's
// normalised depth, the integral reconstructed in closed form (fourier_device.h: ringing and
// clamping). A DSM storage, not a shadow method: its input is exactly the DSM generation walk's
// per-texel visibility function (the sink interface of dsm_storage.h), and faces, clusters,
// receiver bias and filtering are the dsm method's. Passes: `range` (first and last node
// depth), `write` (the nodes replayed, engine/dsm/node_replay.h, and projected). Bytes per texel: 4
// * (4 + 2K): 48 (K = 4), 80 (K = 8), 144 (K = 16). Parameter: frequencies (K). The answer does not
// respect eps: truncation error and ringing remain. Compiled by nvcc when CUDA is on.
#include <memory>

#include "core/error.h"
#include "strategies/storage/basis_storage.h"
#include "strategies/storage/fourier_device.h"

namespace dv {

namespace {

class FourierStorage final : public BasisStorage<FourierStorage> {
 public:
  explicit FourierStorage(const StrategyParams& p)
      : BasisStorage(p, "dsm fourier texels", "dsm_fourier_write",
                     "folded into the coefficients, not stored"),
        frequencies_(p.integer("frequencies")) {}
  std::string name() const override { return "fourier"; }
  int stride() const { return fourier_stride(frequencies_); }
  auto sink() const { return FourierSink{nullptr, frequencies_}; }
  DsmReader reader() const override {
    return DsmReader(FourierReader{data_.const_view(), frequencies_});
  }

 private:
  int frequencies_;
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
