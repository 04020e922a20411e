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
#include "strategies/storage/basis_storage.h"
#include "strategies/storage/moments_device.h"

namespace dv {

namespace {

class MomentsStorage final : public BasisStorage<MomentsStorage> {
 public:
  explicit MomentsStorage(const StrategyParams& p)
      : BasisStorage(p, "dsm moments texels", "dsm_moments_write",
                     "folded into the moments, not stored"),
        moments_(p.integer("moments")),
        bias_(p.number("bias", default_moment_bias(moments_))),
        overestimation_(p.number("overestimation")) {}
  std::string name() const override { return "moments"; }
  int stride() const { return moments_stride(moments_); }
  auto sink() const { return PowerMomentSink{nullptr, moments_}; }
  DsmReader reader() const override {
    return DsmReader(
        MomentsReader{data_.const_view(), moments_, float(bias_), float(overestimation_)});
  }

 private:
  int moments_;
  double bias_;
  double overestimation_;
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
