// Shadow method "shadowmap": conventional depth shadow maps rendered with the tile rasterizer
// from each light (see shadow_map_device.h for the lookup). Parameters: those of depth maps
// (depth_map_param_table()) and focus (1: fit spot and directional maps to what the camera can
// see, Brabec 2003 §4.2). Focusing is geometric and conservative: the map covers the part of the
// scene bounds inside the bounding box of the camera frustum (a control render with read-back, as
// Brabec does, would be tighter); omni faces and queries without a camera (probe) are not focused.
// A focused map depends on the camera, so it is rebuilt when the camera moves. Near and far planes
// are fitted to the casters (the scene's bounds); maps are rebuilt only when the scene data or
// backend changes. Also implements the shared depth maps of depth_maps.h.
#include <algorithm>
#include <limits>
#include <vector>

#include "cuda/buffer.h"
#include "cuda/pass_timer.h"
#include "engine/raster/fitted_light_faces.h"
#include "engine/raster/tile_list_sets.h"
#include "engine/raster/tile_raster.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/texture_sampling.h"
#include "strategies/shadow/depth_maps.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/shadow/translucent_casters.h"

namespace dv {

namespace {

// The region a camera can see: the scene bounds clipped to the bounding box of its frustum.
Aabb visible_region(const Camera& camera, const Aabb& bounds) {
  const RasterProjection p = make_camera_projection(camera, bounds);
  Aabb frustum;
  for (int corner = 0; corner < 8; ++corner)
    frustum.extend(unproject_ndc(p, corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0,
                                 corner & 4 ? 1.0 : -1.0));
  return {glm::max(frustum.lo, bounds.lo), glm::min(frustum.hi, bounds.hi)};
}

// Narrows a face's map to the NDC rectangle that `region` projects to (within the original
// map): an x/y scale and bias after the projection, which leaves w and the near plane alone.
void focus_face(ShadowFace& face, const Aabb& region) {
  if (region.empty()) return;
  double lo[2] = {1.0, 1.0}, hi[2] = {-1.0, -1.0};
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 c(corner & 1 ? region.hi.x : region.lo.x, corner & 2 ? region.hi.y : region.lo.y,
                  corner & 4 ? region.hi.z : region.lo.z);
    const dvec4 clip = world_to_clip_point(face.projection, c);
    if (clip.w <= 0.0) return;  // part of the region is behind the light: keep the whole map
    for (int a = 0; a < 2; ++a) {
      const double ndc = std::clamp(clip[a] / clip.w, -1.0, 1.0);
      lo[a] = std::min(lo[a], ndc);
      hi[a] = std::max(hi[a], ndc);
    }
  }
  if (!(hi[0] > lo[0] && hi[1] > lo[1])) return;
  dmat4 narrow(1.0);
  for (int a = 0; a < 2; ++a) {
    narrow[a][a] = 2.0 / (hi[a] - lo[a]);
    narrow[3][a] = -(hi[a] + lo[a]) / (hi[a] - lo[a]);
  }
  // x' = a x + b w in clip space is NDC' = a NDC + b for either projection.
  face.projection.world_to_clip = narrow * face.projection.world_to_clip;
  face.projection.clip_to_world = glm::inverse(face.projection.world_to_clip);
  face.texel_size *= 0.5 * std::max(hi[0] - lo[0], hi[1] - lo[1]);
}

// Whether a surface goes into the glass layer (when a fragment of it is not opaque enough for
// the depth map).
DV_HD inline bool glass_caster(const ObjectView& o) {
  return o.transmission > 0.0;
}

// Nearest caster depth per texel of one face from its tile lists; `medium_alphas` per object:
// the opacity of its interior medium across it (depth_maps.h). With a glass layer (non-empty
// views) also the nearest glass crossing's depth and the product of the crossing rule over the
// glass crossings the depth map leaves out.
void render_depth_face(Backend backend, const SceneView& s, const ShadowFace& face,
                       const TileListsView& tiles, DepthCasters casters,
                       View<const double> medium_alphas, View<float> depths,
                       View<float> glass_depths, View<vec3> glass_filters) {
  const double min_alpha = casters == DepthCasters::opaque ? 1.0 : kDepthMapOpaqueAlpha;
  const int res = face.projection.width;
  const bool glass = !glass_filters.empty();
  parallel_for(
      backend, "shadow_map_depth", int64_t(res) * res, DV_KERNEL_LAMBDA(int64_t i) {
        const int x = int(i % res), y = int(i / res);
        const PixelRay ray = pixel_ray(face.projection, x, y);
        double nearest = 1e300, nearest_glass = 1e300;
        dvec3 filter(1.0);
        for_each_fragment(tiles, x, y, [&](uint32_t tri) {
          double t;
          bool entering;
          if (!triangle_plane_hit(s, tri, ray.origin, ray.direction, t, entering)) return;
          const dvec3 hit = ray.origin + ray.direction * t;
          const uint32_t object = s.triangle_object[tri];
          const double alpha = max_value(surface_alpha(s, tri, hit), medium_alphas[object]);
          const double depth = shadow_depth(face, hit);
          if (alpha >= min_alpha) {
            nearest = min_value(nearest, depth);
            return;
          }
          const ObjectView& o = s.objects[object];
          if (!glass || !glass_caster(o)) return;
          nearest_glass = min_value(nearest_glass, depth);
          filter *= crossing_transmittance(s, o, tri, ray.direction, hit);
        });
        depths[face.offset + i] = nearest >= 1e300 ? INFINITY : float(nearest);
        if (!glass) return;
        glass_depths[face.offset + i] = nearest_glass >= 1e300 ? INFINITY : float(nearest_glass);
        glass_filters[face.offset + i] = vec3(filter);
      });
}

// An empty face: no caster anywhere, every texel +inf.
void clear_depth_face(Backend backend, const ShadowFace& face, View<float> depths) {
  const int res = face.projection.width;
  parallel_for(
      backend, "shadow_map_clear", int64_t(res) * res,
      DV_KERNEL_LAMBDA(int64_t i) { depths[face.offset + i] = INFINITY; });
}

class ShadowMapMethod final : public ShadowMethod {
 public:
  explicit ShadowMapMethod(const StrategyParams& p)
      : given_(p), params_(DepthMapParams::read(p)), focus_(p.integer("focus") != 0) {}
  std::string name() const override { return "shadowmap"; }
  nlohmann::json params() const override { return given_.echo(); }
  nlohmann::json stats() const override {
    return {{"maps_built", builds_},
            {"prepare_calls", prepare_calls_},
            {"faces", faces_built_},
            {"bytes", maps_.bytes()},
            {"last_build_ms", build_ms_}};
  }

  ShadowSourceVariant prepare(const SceneData& scene, Backend backend,
                              const Camera* view) override {
    const bool focused = focus_ && view;
    const bool camera_moved = focused && !(has_camera_ && same_camera(*view, camera_));
    if (prepared_for_ != &scene || backend_ != backend || camera_moved || focused != was_focused_) {
      if (focused) camera_ = *view, has_camera_ = true;
      build(scene, backend, focused ? view : nullptr);
    }
    ++prepare_calls_;
    return source_;
  }

 private:
  static bool same_camera(const Camera& a, const Camera& b) {
    return a.position == b.position && a.target == b.target && a.up == b.up &&
           a.fov_deg == b.fov_deg && a.width == b.width && a.height == b.height &&
           a.near_plane == b.near_plane;
  }

  void build(const SceneData& scene, Backend backend, const Camera* focus_on) {
    const SceneView& s = scene.view();
    PassTimer timer(backend);
    LightMapLayout layout = fitted_light_map_layout(
        scene.host_lights(), s.bounds, scene.host_object_bounds(), s.diagonal, params_.res);
    if (focus_on)
      for (const ShadowLight& l : layout.lights)
        if (l.face_count == 1)
          focus_face(layout.faces[l.first_face], visible_region(*focus_on, s.bounds));
    maps_ = render_depth_maps(backend, scene, layout, params_.res, DepthCasters::surfaces);
    source_ = maps_.source(s, params_);
    prepared_for_ = &scene;
    backend_ = backend;
    was_focused_ = focus_on != nullptr;
    ++builds_;
    build_ms_ = timer.stop();
    faces_built_ = int(layout.faces.size());
  }

  StrategyParams given_;  // resolved: echoes the table's keys
  DepthMapParams params_;
  bool focus_;
  Camera camera_;
  bool has_camera_ = false, was_focused_ = false;
  DepthMaps maps_;
  ShadowMapSource source_{};
  const SceneData* prepared_for_ = nullptr;
  Backend backend_ = Backend::cpu;
  int builds_ = 0, prepare_calls_ = 0, faces_built_ = 0;
  double build_ms_ = 0.0;
};

}  // namespace

DepthMapParams DepthMapParams::read(const StrategyParams& p) {
  DepthMapParams d;
  d.res = p.integer("res");
  d.pcf = p.integer("pcf");
  d.bias = p.number("bias");
  d.slope = p.number("slope");
  return d;
}

const ParamTable& depth_map_param_table() {
  static const ParamTable table = [] {
    const DepthMapParams d;
    const double inf = std::numeric_limits<double>::infinity();
    return ParamTable{
        integer_param("res", d.res, 1, kMaxRasterSide, "texels per side of each map"),
        integer_param("pcf", d.pcf, 1, 16, "side of the percentage-closer kernel; 1: unfiltered"),
        number_param("bias", d.bias, -1.0, inf,
                     "receiver depth bias in world units; < 0: 1e-4 of the scene diagonal"),
        number_param("slope", d.slope, 0.0, inf,
                     "texel sizes times the receiver's tangent to the light added to the bias")};
  }();
  return table;
}

nlohmann::json DepthMapParams::json() const {
  return {{"res", res}, {"pcf", pcf}, {"bias", bias}, {"slope", slope}};
}

ShadowMapSource DepthMaps::source(const SceneView& s, const DepthMapParams& params) const {
  return {s.lights,
          lights.const_view(),
          faces.const_view(),
          depths.const_view(),
          res,
          params.pcf,
          params.bias_for(s),
          params.slope,
          glass_depths.const_view(),
          glass_filters.const_view()};
}

int64_t DepthMaps::bytes() const {
  return int64_t(depths.bytes() + glass_depths.bytes() + glass_filters.bytes());
}

DepthMaps render_depth_maps(Backend backend, const SceneData& scene, const LightMapLayout& layout,
                            int res, DepthCasters casters, const std::vector<uint8_t>* rendered) {
  const SceneView& s = scene.view();
  const Memory memory = memory_of(backend);
  std::vector<double> medium = medium_crossing_alphas(scene);
  for (double& a : medium) a = 1.0 - (1.0 - a) * (1.0 - a);  // entering and leaving
  const Buffer<double> medium_alphas(memory, medium, "depth map medium opacities");
  DepthMaps maps;
  maps.res = res;
  maps.depths = Buffer<float>(memory, layout.texel_count(), "shadow map depths");
  bool glass = false;
  for (const ObjectView& o : scene.host_objects()) glass |= glass_caster(o);
  if (glass) {
    // +inf (no glass) on faces left empty; rendered faces overwrite theirs.
    const std::vector<float> none(size_t(layout.texel_count()), INFINITY);
    maps.glass_depths = Buffer<float>(memory, none, "shadow map glass depths");
    maps.glass_filters = Buffer<vec3>(memory, layout.texel_count(), "shadow map glass filters");
  }
  // The faces to render are binned in sets (tile_list_sets.h: the rasterizer's passes once a
  // set, not once a face), then each face's depths come from its lists.
  std::vector<size_t> to_render;
  std::vector<RasterProjection> projections;
  for (size_t i = 0; i < layout.faces.size(); ++i) {
    if (rendered && !(*rendered)[i]) {
      clear_depth_face(backend, layout.faces[i], maps.depths.view());
    } else {
      to_render.push_back(i);
      projections.push_back(layout.faces[i].projection);
    }
  }
  size_t face = 0;
  for (const TileListSet& lists :
       rasterize_tile_sets(backend, s.vertices, s.triangles, projections))
    for (int k = 0; k < lists.projections(); ++k) {
      if (lists.stats[size_t(k)].overflow)
        throw Error("shadowmap: tile lists overflowed while rendering a shadow map");
      render_depth_face(backend, s, layout.faces[to_render[face++]], lists.view(k), casters,
                        medium_alphas.const_view(), maps.depths.view(), maps.glass_depths.view(),
                        maps.glass_filters.view());
    }
  maps.faces = Buffer<ShadowFace>(memory, layout.faces, "shadow map faces");
  maps.lights = Buffer<ShadowLight>(memory, layout.lights, "shadow map lights");
  return maps;
}

void register_shadow_maps(Registry<ShadowMethod>& registry) {
  registry.add("shadowmap",
               "depth shadow maps from the tile rasterizer, PCF; a surface casts where its alpha "
               "(texture coverage; an interior medium's opacity across the object) is >= 0.5",
               join(depth_map_param_table(),
                    {integer_choice_param("focus", 0, {0, 1},
                                          "1: fit spot and directional maps to the camera's view "
                                          "(Brabec 2003 4.2)")}),
               [](const StrategyParams& p) { return std::make_unique<ShadowMapMethod>(p); });
}

}  // namespace dv
