// Storage strategy `moments`: moment-based transmittance (Muenstermann, Krumpen, Klein & Peters
// 2018, "Moment-Based Order-Independent Transparency"; Peters & Klein 2015, "Moment Shadow
// Mapping"): per texel n = 4 or 6 power moments of optical depth over depth, reconstruction
// with the bias and bounds of power_moments.h. A DSM storage, not a shadow method: its input is
// exactly the DSM generation walk's per-texel visibility function (the sink interface of
// dsm_storage.h), and everything around the texel (faces, clusters, receiver bias, bilinear
// filter) is the dsm method's; only what a texel keeps and how it answers differs. Passes:
// `range` (first and last node depth), `write` (the nodes replayed and folded into moments).
// Bytes per texel: 4 * (4 + n): 32 (n = 4), 40 (n = 6). Parameters: the table at its
// registration. The answer is biased: a bound blended between the
// Chebyshev-Markov-Krein bounds, not the function; it does not respect eps. Compiled by nvcc
// when CUDA is on.
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "dsm/storage/basis_texel_write.h"
#include "dsm/storage/dsm_storage.h"
#include "dsm/storage/moments_device.h"

namespace dv {

namespace {

class MomentsStorage final : public DsmStorage {
 public:
  explicit MomentsStorage(const StrategyParams& p)
      : params_(p),
        moments_(p.integer("moments")),
        bias_(p.number("bias", default_moment_bias(moments_))),
        overestimation_(p.number("overestimation")) {}
  std::string name() const override { return "moments"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const int stride = moments_stride(moments_);
    ensure_buffer(data_, memory_of(c.backend), c.generator.texel_count() * stride,
                  "dsm moments texels");
    generate_basis_texels(c, scratch_, "dsm_moments_write", PowerMomentSink{nullptr, moments_},
                          stride, data_.view());
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
    nlohmann::json figures = {
        {"bytes_per_texel", int64_t(sizeof(float)) * moments_stride(moments_)},
        {"nodes", "folded into the moments, not stored"}};
    figures.update(scratch_.figures());
    return figures;
  }

 private:
  StrategyParams params_;
  int moments_;
  double bias_;
  double overestimation_;
  Buffer<float> data_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_moments_storage(Registry<DsmStorage>& registry) {
  registry.add("moments",
               "Muenstermann et al. 2018 / Peters & Klein 2015: 4 or 6 power moments of optical "
               "depth per texel, biased bound",
               {integer_choice_param("moments", 4, {4, 6}, "power moments per texel"),
                [] {
                  ParamSpec bias = derived(number_param(
                      "bias", 0.0, 0.0, 1.0,
                      "moment bias alpha (default: 5e-7 for 4 moments, 5e-6 for 6, the "
                      "paper's 32-bit values)"));
                  bias.hi_open = true;
                  return bias;
                }(),
                number_param("overestimation", 0.25, 0.0, 1.0,
                             "weight at the query depth between the lower (0) and upper (1) "
                             "bound (the paper's 0.25)")},
               [](const StrategyParams& p) { return std::make_unique<MomentsStorage>(p); });
}

}  // namespace dv
