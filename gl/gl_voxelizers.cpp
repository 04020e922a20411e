// The registered OpenGL voxelizers (see gl_voxelizers.h).
#include "gl/gl_voxelizers.h"

#include <functional>
#include <memory>

#include "core/error.h"
#include "gl/egl_context.h"
#include "gl/gl_atlas.h"
#include "gl/gl_slicemap.h"
#include "strategies/voxelizer/atlas_packing.h"
#include "strategies/voxelizer/atlas_voxelizer.h"

namespace dv::gl {

namespace {

using GlVoxelize = std::function<VoxelizeResult(const TriangleSoup&, const GridSpec&)>;

// A GL voxelizer: its own headless context, host grids.
class GlVoxelizer : public Voxelizer {
 public:
  GlVoxelizer(std::string name, nlohmann::json params, GlVoxelize run)
      : name_(std::move(name)), params_(std::move(params)), run_(std::move(run)) {}
  std::string name() const override { return name_; }
  nlohmann::json params() const override { return params_; }
  bool supports(Backend backend) const override { return backend == Backend::cpu; }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    const std::string where = name_ + " (gl)";
    if (!supports(backend))
      throw InputError(where, "returns host grids: call it with Backend::cpu");
    if (!context_) {
      std::string why;
      context_ = EglContext::create_headless(&why);
      if (!context_) throw Error(where + ": no headless OpenGL 4.5 context: " + why);
    }
    context_->make_current();
    return run_(soup, spec);
  }

 private:
  std::string name_;
  nlohmann::json params_;
  GlVoxelize run_;
  std::unique_ptr<EglContext> context_;
};

std::unique_ptr<Voxelizer> make_atlas(const StrategyParams& params) {
  const int side = params.integer("atlas");
  return std::make_unique<GlVoxelizer>("atlas", params.echo(),
                                       [side](const TriangleSoup& soup, const GridSpec& spec) {
                                         return voxelize_atlas_gl(soup, spec, side);
                                       });
}

}  // namespace

void register_gl_voxelizers(Registry<Voxelizer>& registry) {
  registry.add("slicemap", "OpenGL slicemap through headless EGL (imageAtomicOr, any depth)", {},
               [](const StrategyParams&) {
                 return std::make_unique<GlVoxelizer>("slicemap", nlohmann::json::object(),
                                                      voxelize_slicemap_gl);
               });
  registry.add("atlas",
               "OpenGL atlas through headless EGL: the triangle atlas rendered into an RGBA32F "
               "position texture, then one GL point per texel (imageAtomicOr)",
               {atlas_side_param()}, make_atlas);
}

void install_gl_voxelizers() {
  static const bool installed = [] {
    register_gl_voxelizers(gl_voxelizer_registry());
    return true;
  }();
  (void)installed;
}

}  // namespace dv::gl
