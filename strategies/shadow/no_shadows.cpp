// Shadow method "none": lights are never occluded. The baseline for timing the rest.
#include "strategies/shadow/shadow_method.h"

namespace dv {

namespace {

class NoShadows final : public ShadowMethod {
 public:
  std::string name() const override { return "none"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  ShadowSourceVariant prepare(const SceneData&, Backend, const Camera*) override {
    return NoShadowSource{};
  }
};

}  // namespace

void register_no_shadows(Registry<ShadowMethod>& registry) {
  registry.add("none", "no shadows: every light reaches every point", {},
               [](const StrategyParams&) { return std::make_unique<NoShadows>(); });
}

}  // namespace dv
