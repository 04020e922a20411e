// Kernel side of deep-shadow-map generation: per texel of every light's faces, the ray through
// the texel centre is walked with the renderer's fragment walk over the face's tile lists
// (engine/raster/raster_fragments.h) and the visibility payload (engine/dsm/visibility_payload.h),
// and the streaming compressor (engine/dsm/visibility_compressor.h) writes the nodes into a storage
// strategy's sink. Threads are numbered tile by tile: 64 consecutive threads are one 8x8 texel
// tile, which is the rasterizer's tile (one tile list per warp) and the chunked storage's block.
// Host and device code; engine/dsm/dsm_generation.h builds it.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/dsm/object_mask.h"
#include "engine/dsm/prefilter.h"
#include "engine/dsm/visibility_compressor.h"
#include "engine/dsm/visibility_payload.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/raster_fragments.h"

namespace dv {

// Texels per side of a generation block: a raster tile (texel_of_thread takes them tile by tile).
inline constexpr int kDsmBlockSide = kTileSide;

// What generation left in one texel, for figures, heatmaps and the overflow report.
struct DsmTexelRecord {
  int32_t nodes = 0;   // nodes the compressed function needs
  int32_t stored = 0;  // nodes the storage holds (fewer after an overflow)
  float error = 0.0f;  // bound on max |V' - V| reached (above eps only after an overflow)
  uint32_t flags = 0;  // DsmTexelFlag bits
};

enum DsmTexelFlag : uint32_t {
  kDsmStorageOverflow = 1u,  // the storage refused nodes: it holds a prefix of V'
  kDsmWalkOverflow = 2u,     // the walk hit kMaxHitsPerPixel or kMaxInsideObjects, or a
                             // pre-filtering sub-ray overflowed its node array
  kDsmRecompressed = 4u,     // stored with a larger eps than asked (texture3d's policy)
  kDsmNodesMerged = 8u,      // a fixed-node storage (beer, avsm) kept fewer nodes than the
                             // function has: V' is within the record's error bound only
};

struct DsmTexel {
  int face, x, y;
  int64_t index;  // face * res^2 + y * res + x: the texel's place in every per-texel array
};

// A sink wrapper that remembers how much was stored and the last stored value.
template <class Sink>
struct TrackingSink {
  Sink inner;
  int stored = 0;
  float last_v = 1.0f;
  DV_HD bool emit(float z, float v) {
    if (!inner.emit(z, v)) return false;
    ++stored, last_v = v;
    return true;
  }
};

template <class Sink>
struct DsmTexelResult {
  Sink sink;  // the sink after the texel (storages read their state from it)
  DsmTexelRecord record;
  float final_visibility = 1.0f;  // V where the walk ended (the exact function's last value)
};

struct DsmGenerator {
  SceneView scene;
  View<const ShadowFace> faces;
  View<const TileListsView> lists;  // per face
  View<const InsideSet> ray_media;  // per face: media containing its rays' origin
  int resolution = 0;
  int subrays = 1;                    // > 1: pre-filtered texels (engine/dsm/prefilter.h)
  PrecompressedTables tables;         // bins > 0: volume steps from pre-compressed tables
  double step_scale = 1.0;            // multiplies the volumes' steps
  View<const uint32_t> object_masks;  // per face mask_words words (engine/dsm/object_mask.h)
  int mask_words = 0;                 // 0: every face sees every object

  DV_HD ObjectMask mask_of(int face) const {
    return mask_words == 0 ? ObjectMask{} : ObjectMask{object_masks, int64_t(face) * mask_words};
  }

  DV_HD int64_t texel_count() const { return faces.size * int64_t(resolution) * resolution; }
  DV_HD int64_t thread_count() const {
    return faces.size * tiled_thread_count(resolution, resolution);
  }
  // The generation block (8x8 tile, over all faces) thread i belongs to.
  DV_HD int64_t block_of_thread(int64_t i) const { return i / (kDsmBlockSide * kDsmBlockSide); }

  // False for the padding threads of tiles that stick out of the map.
  DV_HD bool texel_of_thread(int64_t i, DsmTexel& t) const {
    const int64_t per_face = tiled_thread_count(resolution, resolution);
    t.face = int(i / per_face);
    if (!pixel_of_tiled_thread(i % per_face, resolution, resolution, t.x, t.y)) return false;
    t.index = faces[t.face].offset + int64_t(t.y) * resolution + t.x;
    return true;
  }

  template <class Target>
  DV_HD VisibilityPayload<Target> make_payload(Target& target, const PixelRay& ray,
                                               double eps) const {
    VisibilityPayload<Target> p{scene, target, ray.origin, ray.direction, eps};
    p.tables = tables;
    p.step_scale = step_scale;
    return p;
  }

  // Walks `ray` of face `face` into `payload` over the crossings of `fragments` with the face's
  // objects, from where the face's near plane cuts the ray, inside the media (of those objects)
  // there; the status's overflow includes that of the walk to the near plane.
  template <class Fragments, class Target>
  DV_HD WalkStatus walk_from_near_plane(int face, const PixelRay& ray, const Fragments& fragments,
                                        VisibilityPayload<Target>& payload) const {
    const ObjectMask mask = mask_of(face);
    const NearPlaneStart front =
        masked_start_at_near_plane(scene, faces[face].projection, ray, ray_media[face], mask);
    const MaskedFragments<Fragments> masked{&scene, fragments, mask};
    WalkStatus status =
        walk_fragments(scene, masked, front.status.inside, front.t, front.t, 1e300, payload);
    status.overflow |= front.status.overflow;
    return status;
  }

  // Walks texel t's ray into `target` (push / push_step), sampling constant media for error
  // bound eps; returns the walk's status and the visibility where it ended. With `colour` the
  // walk also sums the optical depths of the colour side channel (engine/dsm/dsm_colour.h).
  template <class Target>
  DV_HD WalkStatus walk(const DsmTexel& t, double eps, Target& target, double& final_visibility,
                        ColourDepth* colour = nullptr) const {
    const PixelRay ray = pixel_ray(faces[t.face].projection, t.x, t.y);
    VisibilityPayload<Target> payload = make_payload(target, ray, eps);
    payload.track_colour = colour != nullptr;
    const WalkStatus status = walk_from_near_plane(
        t.face, ray, RasterFragments{&scene, lists[t.face], t.x, t.y, ray.origin, ray.direction},
        payload);
    final_visibility = payload.visibility;
    if (colour) *colour = payload.tinted;
    return status;
  }

  // Generates texel t's compressed function with error bound eps into `sink`. The walk samples
  // constant media for `sample_eps` (default: eps), so that a texel compressed again with a
  // larger bound keeps the same samples.
  template <class Sink>
  DV_HD DsmTexelResult<Sink> generate(const DsmTexel& t, float eps, Sink sink,
                                      float sample_eps = -1.0f) const {
    if (sample_eps < 0.0f) sample_eps = eps;
    if (subrays > 1) return generate_prefiltered(t, eps, sink, sample_eps);
    VisibilityCompressor<TrackingSink<Sink>> compressor(eps, TrackingSink<Sink>{sink});
    double final_visibility = 1.0;
    const WalkStatus status = walk(t, sample_eps, compressor, final_visibility);
    compressor.finish();
    return result(compressor, status.overflow, 0.0f, float(final_visibility));
  }

  // The same from `subrays` jittered sub-rays averaged (engine/dsm/prefilter.h).
  template <class Sink>
  DV_HD DsmTexelResult<Sink> generate_prefiltered(const DsmTexel& t, float eps, Sink sink,
                                                  float sample_eps) const {
    const ShadowFace& f = faces[t.face];
    SubrayNodes nodes;
    nodes.rays = min_value(subrays, kMaxSubrays);
    int side = 1;
    while ((side + 1) * (side + 1) <= nodes.rays) ++side;
    bool overflow = false;
    float sub_error = 0.0f;
    double final_visibility = 0.0;
    for (int k = 0; k < nodes.rays; ++k) {
      const double px = t.x + (double(k % side) + subray_jitter(t.index, k, 0)) / side;
      const double py = t.y + (double(k / side % side) + subray_jitter(t.index, k, 1)) / side;
      const PixelRay ray = image_point_ray(f.projection, px, py);
      VisibilityCompressor<ArrayNodeSink> sub(0.5f * eps,
                                              ArrayNodeSink{nodes.z[k], nodes.v[k], kSubrayNodes});
      VisibilityPayload<VisibilityCompressor<ArrayNodeSink>> payload =
          make_payload(sub, ray, sample_eps);
      const WalkStatus status = walk_from_near_plane(
          t.face, ray, BvhFragments{&scene, make_sheared_ray(ray.origin, ray.direction), 1e300},
          payload);
      sub.finish();
      nodes.count[k] = sub.sink().count;
      overflow |= status.overflow || sub.stats().overflow;
      sub_error = max_value(sub_error, sub.stats().max_error);
      final_visibility += payload.visibility / nodes.rays;
    }
    VisibilityCompressor<TrackingSink<Sink>> compressor(0.5f * eps, TrackingSink<Sink>{sink});
    push_average(nodes, compressor);
    compressor.finish();
    return result(compressor, overflow, sub_error, float(final_visibility));
  }

  // The texel's record from its compressor; `extra_error` adds the error of earlier stages.
  template <class Sink>
  DV_HD static DsmTexelResult<Sink> result(
      const VisibilityCompressor<TrackingSink<Sink>>& compressor, bool walk_overflow,
      float extra_error, float final_visibility) {
    const VisibilityCompressionStats& stats = compressor.stats();
    const TrackingSink<Sink>& tracked = compressor.sink();
    return {tracked.inner,
            texel_record(stats.nodes, stats.max_error + extra_error, tracked, final_visibility,
                         walk_overflow),
            final_visibility};
  }

  // The record of a texel whose function has `nodes` nodes within `error` of the walk's, of
  // which `tracked` took a prefix (all but after a refusal: the compressor emits no more then).
  template <class Sink>
  DV_HD static DsmTexelRecord texel_record(int nodes, float error,
                                           const TrackingSink<Sink>& tracked,
                                           float final_visibility, bool walk_overflow) {
    DsmTexelRecord r;
    r.nodes = nodes;
    r.stored = tracked.stored;
    r.error = error;
    if (tracked.stored < nodes) {
      // The prefix is within the bound; beyond it V' stays at the last stored value while V
      // falls to where the walk ended.
      r.flags |= kDsmStorageOverflow;
      r.error = max_value(r.error, tracked.last_v - final_visibility);
    }
    if (walk_overflow) r.flags |= kDsmWalkOverflow;
    return r;
  }
};

}  // namespace dv
