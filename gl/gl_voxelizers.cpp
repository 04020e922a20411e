// The registered OpenGL voxelizers (see gl_voxelizers.h).
#include "gl/gl_voxelizers.h"

#include <memory>

#include "core/error.h"
#include "gl/egl_context.h"
#include "gl/gl_slicemap.h"

namespace dv::gl {

namespace {

class GlSlicemapVoxelizer : public Voxelizer {
 public:
  std::string name() const override { return "slicemap"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  bool supports(Backend backend) const override { return backend == Backend::cpu; }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    if (!supports(backend))
      throw InputError("slicemap (gl)", "returns host grids: call it with Backend::cpu");
    if (!context_) {
      std::string why;
      context_ = EglContext::create_headless(&why);
      if (!context_) throw Error("slicemap (gl): no headless OpenGL 4.5 context: " + why);
    }
    context_->make_current();
    return voxelize_slicemap_gl(soup, spec);
  }

 private:
  std::unique_ptr<EglContext> context_;
};

}  // namespace

void register_gl_voxelizers(Registry<Voxelizer>& registry) {
  registry.add("slicemap", "OpenGL slicemap through headless EGL (imageAtomicOr, any depth)",
               [](const StrategyParams&) { return std::make_unique<GlSlicemapVoxelizer>(); });
}

}  // namespace dv::gl
