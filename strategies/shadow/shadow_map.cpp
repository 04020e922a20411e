// Shadow method "shadowmap": conventional depth shadow maps rendered with the tile rasterizer
// from each light (see shadow_map_source.h for the lookup). Parameters: res (texels per side,
// default 1024), pcf (kernel side, default 2; 1 = unfiltered), bias (world units, default
// 1e-4 of the scene diagonal), slope (texel sizes added to the bias, default 1.5), focus (1:
// fit spot and directional maps to what the camera can see, Brabec 2003 §4.2; default 0).
// Focusing is geometric and conservative: the map covers the part of the scene bounds inside
// the bounding box of the camera frustum (a control render with read-back, as Brabec does,
// would be tighter); omni faces and queries without a camera (probe) are not focused. A
// focused map depends on the camera, so it is rebuilt when the camera moves. Near and far planes
// are fitted to the casters (the scene's bounds); maps are rebuilt only when the scene data or
// backend changes.
#include <algorithm>

#include "core/buffer.h"
#include "core/pass_timer.h"
#include "renderer/raster/tile_raster.h"
#include "scene/ray_query.h"
#include "strategies/shadow/shadow_map_source.h"
#include "strategies/shadow/shadow_method.h"

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

// Nearest caster depth per texel of one face.
void render_depth_face(Backend backend, const SceneView& s, const ShadowFace& face,
                       View<float> depths) {
  const TileLists lists = rasterize_tiles(backend, s, face.projection);
  if (lists.stats.overflow)
    throw Error("shadowmap: tile lists overflowed while rendering a shadow map");
  const TileListsView tiles = lists.view();
  const int res = face.projection.width;
  parallel_for(
      backend, "shadow_map_depth", int64_t(res) * res, DV_KERNEL_LAMBDA(int64_t i) {
        const int x = int(i % res), y = int(i / res);
        const PixelRay ray = pixel_ray(face.projection, x, y);
        double nearest = 1e300;
        for_each_fragment(tiles, x, y, [&](uint32_t tri) {
          double t;
          bool entering;
          if (s.objects[s.triangle_object[tri]].alpha <= 0.0 ||
              !triangle_plane_hit(s, tri, ray.origin, ray.direction, t, entering))
            return;
          nearest = min_value(nearest, shadow_depth(face, ray.origin + ray.direction * t));
        });
        depths[face.offset + i] = nearest >= 1e300 ? INFINITY : float(nearest);
      });
}

class ShadowMapMethod final : public ShadowMethod {
 public:
  explicit ShadowMapMethod(const StrategyParams& p)
      : res_(p.integer("res", 1024)),
        pcf_(p.integer("pcf", 2)),
        bias_(p.number("bias", -1.0)),
        slope_(p.number("slope", 1.5)),
        focus_(p.integer("focus", 0) != 0) {
    if (res_ < 1 || res_ > kMaxRasterSide)
      throw InputError("shadowmap res", "must lie in [1, 65536]");
    if (pcf_ < 1 || pcf_ > 16) throw InputError("shadowmap pcf", "must lie in [1, 16]");
  }
  std::string name() const override { return "shadowmap"; }
  nlohmann::json params() const override {
    return {{"res", res_},
            {"pcf", pcf_},
            {"bias", bias_ >= 0.0 ? nlohmann::json(bias_) : nlohmann::json("auto")},
            {"slope", slope_},
            {"focus", focus_}};
  }
  nlohmann::json stats() const override {
    return {{"maps_built", builds_},
            {"prepare_calls", prepare_calls_},
            {"faces", faces_built_},
            {"bytes", depths_.bytes()},
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
    LightMapLayout layout = light_map_layout(scene.host_lights(), s.bounds, s.diagonal, res_);
    std::vector<ShadowFace>& faces = layout.faces;
    if (focus_on)
      for (const ShadowLight& l : layout.lights)
        if (l.face_count == 1) focus_face(faces[l.first_face], visible_region(*focus_on, s.bounds));
    const int64_t texels = layout.texels_per_face;
    const Memory memory = backend == Backend::cuda ? Memory::device : Memory::host;
    depths_ = Buffer<float>(memory, texels * int64_t(faces.size()), "shadow map depths");
    for (const ShadowFace& f : faces) render_depth_face(backend, s, f, depths_.view());
    faces_ = Buffer<ShadowFace>(memory, faces, "shadow map faces");
    light_faces_ = Buffer<ShadowLight>(memory, layout.lights, "shadow map lights");
    const double bias = bias_ >= 0.0 ? bias_ : 1e-4 * s.diagonal;
    source_ = ShadowMapSource{s.lights,
                              light_faces_.const_view(),
                              faces_.const_view(),
                              depths_.const_view(),
                              res_,
                              pcf_,
                              bias,
                              slope_};
    prepared_for_ = &scene;
    backend_ = backend;
    was_focused_ = focus_on != nullptr;
    ++builds_;
    build_ms_ = timer.stop();
    faces_built_ = int(faces.size());
  }

  int res_, pcf_;
  double bias_, slope_;
  bool focus_;
  Camera camera_;
  bool has_camera_ = false, was_focused_ = false;
  Buffer<float> depths_;
  Buffer<ShadowFace> faces_;
  Buffer<ShadowLight> light_faces_;
  ShadowMapSource source_{};
  const SceneData* prepared_for_ = nullptr;
  Backend backend_ = Backend::cpu;
  int builds_ = 0, prepare_calls_ = 0, faces_built_ = 0;
  double build_ms_ = 0.0;
};

}  // namespace

void register_shadow_maps(Registry<ShadowMethod>& registry) {
  registry.add(
      "shadowmap",
      "depth shadow maps from the tile rasterizer, PCF (params: res, pcf, bias, slope, focus)",
      [](const StrategyParams& p) { return std::make_unique<ShadowMapMethod>(p); });
}

}  // namespace dv
