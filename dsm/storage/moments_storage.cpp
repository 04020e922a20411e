// Storage strategy `moments`: moment-based transmittance (Muenstermann, Krumpen, Klein & Peters
// 2018, "Moment-Based Order-Independent Transparency"; Peters & Klein 2015, "Moment Shadow
// Mapping"): per texel n = 4 or 6 power moments of optical depth over depth, reconstruction
// with the bias and bounds of power_moments.h. A DSM storage, not a shadow method: its input is
// exactly the DSM generation walk's per-texel visibility function (the sink interface of
// dsm_storage.h), and everything around the texel (faces, clusters, receiver bias, bilinear
// filter) is the dsm method's; only what a texel keeps and how it answers differs. Passes:
// `range` (first and last node depth), `write` (a second walk folding the nodes into moments).
// Bytes per texel: 4 * (4 + n): 32 (n = 4), 40 (n = 6). Parameters: moments (4 | 6, default
// 4), bias (moment bias alpha; default 5e-7 for 4, 5e-6 for 6 moments, the paper's 32-bit
// values), overestimation (the weight at the query depth between the lower (0) and upper (1)
// bound, default 0.25 as in the paper). The answer is biased: a bound blended between the
// Chebyshev-Markov-Krein bounds, not the function; it does not respect eps. Compiled by nvcc
// when CUDA is on.
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "dsm/storage/basis_texel_write.h"
#include "dsm/storage/dsm_storage.h"
#include "dsm/storage/moments_device.h"
#include "dsm/storage/texel_depth_ranges.h"

namespace dv {

namespace {

class MomentsStorage final : public DsmStorage {
 public:
  explicit MomentsStorage(const StrategyParams& p)
      : moments_(p.integer("moments", 4)),
        bias_(p.number("bias", default_moment_bias(moments_))),
        overestimation_(p.number("overestimation", 0.25)) {
    if (moments_ != 4 && moments_ != 6) throw InputError("moments moments", "must be 4 or 6");
    if (!(bias_ >= 0.0 && bias_ < 1.0)) throw InputError("moments bias", "must lie in [0, 1)");
    if (!(overestimation_ >= 0.0 && overestimation_ <= 1.0))
      throw InputError("moments overestimation", "must lie in [0, 1]");
  }
  std::string name() const override { return "moments"; }
  nlohmann::json params() const override {
    return {{"moments", moments_}, {"bias", bias_}, {"overestimation", overestimation_}};
  }

  void generate(const DsmGenerationContext& c) override {
    const int stride = moments_stride(moments_);
    ensure_buffer(data_, memory_of(c.backend), c.generator.texel_count() * stride,
                  "dsm moments texels");
    timed_pass(c, "range", [&] { write_texel_depth_ranges(c, data_.view(), stride); });
    timed_pass(c, "write", [&] {
      write_basis_texels(c, "dsm_moments_write", PowerMomentSink{nullptr, moments_}, stride,
                         data_.view());
    });
  }

  DsmReader reader() const override {
    DsmReader r;
    r.kind = DsmReaderKind::moments;
    r.moments = {data_.const_view(), moments_, float(bias_), float(overestimation_)};
    return r;
  }
  int64_t bytes_allocated() const override { return data_.bytes(); }
  // Nodes are folded into the moments, not stored.
  // Basis coefficients: its error is measured against the oracle, not bounded by eps.
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return 0; }
  nlohmann::json own_figures() const override {
    return {{"bytes_per_texel", int64_t(sizeof(float)) * moments_stride(moments_)},
            {"nodes", "folded into the moments, not stored"}};
  }

 private:
  int moments_;
  double bias_;
  double overestimation_;
  Buffer<float> data_;
};

}  // namespace

void register_moments_storage(Registry<DsmStorage>& registry) {
  registry.add("moments",
               "Muenstermann et al. 2018 / Peters & Klein 2015: 4 or 6 power moments of optical "
               "depth per texel, biased bound (params: moments=4|6, bias, overestimation)",
               [](const StrategyParams& p) { return std::make_unique<MomentsStorage>(p); });
}

}  // namespace dv
