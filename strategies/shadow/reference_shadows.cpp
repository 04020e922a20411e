// Shadow method "reference": the exact transmittance oracle evaluated per shaded sample.
#include "engine/oracle/transmittance.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

namespace {

class ReferenceShadows final : public ShadowMethod {
 public:
  std::string name() const override { return "reference"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  // The oracle's fixed accuracy (compile-time constants, not parameters).
  nlohmann::json stats() const override {
    return {{"volume_integral", "closed form per cell (engine/oracle/volume_chord.h)"},
            {"end_tolerance", kOracleEndTolerance},
            {"max_volume_crossings", kMaxVolumeCrossings}};
  }
  ShadowSourceVariant prepare(const SceneData& scene, Backend, const Camera*) override {
    return ReferenceShadowSource{scene.view()};
  }
};

}  // namespace

void register_reference_shadows(Registry<ShadowMethod>& registry) {
  registry.add("reference", "exact transmittance oracle per shaded sample (ground truth, slow)", {},
               [](const StrategyParams&) { return std::make_unique<ReferenceShadows>(); });
}

}  // namespace dv
