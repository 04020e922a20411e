// Kernel side of transmittance shadow mapping (Buchacher 2014 §5.1): per light face a depth
// shadow map of the opaque casters (alpha >= 1 at the fragment: texture cut-outs are cut per
// texel), tested first, and a binary voxel grid over the face's frustum
// (strategies/voxelizer/frustum_grid.h) of the translucent casters (0 < alpha < 1, media
// boundaries included: translucent_casters.h). The light reaching p is the opaque map's
// answer times (1 - a)^n, n the set voxels of p's column in the slices strictly in front of
// p's slice, a the casters' (mean) opacity; the powers come from a table so that CPU and CUDA
// agree exactly. A surface point's depth is
// biased towards the light like the shadow map's (receiver_depth), so that the receiver's own
// surface voxel is not counted; points not on a surface are not biased. Glass (transmission > 0)
// is not voxelized: the opaque map's glass layer (shadow_map_device.h) carries it, in colour.
// Interiors (media, volumes) are represented only by their boundaries. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/shadow_receiver.h"
#include "strategies/shadow/shadow_map_device.h"
#include "strategies/voxelizer/voxel_geometry.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

struct TransmittanceSlicemapSource {
  ShadowMapSource opaque;           // its faces are the grids' faces (same indices)
  View<const GridTransform> grids;  // per face; empty when there are no translucent casters
  View<uint32_t> words;             // per face res x res x slices bits (VoxelGridView layout)
  View<const double> attenuation;   // (1 - a)^n for n = 0 .. slices
  int slices = 0;

  using Cursor = ShadowMapSource::Cursor;

  DV_HD double transmittance(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return luminance(transmittance_rgb(cursor, r, light));
  }

  DV_HD dvec3 transmittance_rgb(Cursor& cursor, const ShadowReceiver& r, int light) const {
    const dvec3 lit = opaque.transmittance_rgb(cursor, r, light);
    if (max_value(lit.x, max_value(lit.y, lit.z)) == 0.0 || grids.empty()) return lit;
    const int face = face_of(opaque.light_faces[light], opaque.lights[light], r.point);
    return lit * attenuation[slices_in_front(face, r)];
  }

  // Set voxels of the receiver's column in front of its (biased) slice on `face`.
  DV_HD int slices_in_front(int face, const ShadowReceiver& r) const {
    const dvec3& p = r.point;
    const GridTransform& t = grids[face];
    const int res = opaque.resolution;
    const dvec3 g = t.apply(p);  // columns from the projection
    const int x = point_voxel(g.x, res), y = point_voxel(g.y, res);
    if (x < 0 || y < 0) return 0;
    const double biased = receiver_depth(opaque.faces[face], r, t.axial_depth(p), opaque.bias,
                                         opaque.slope_bias, 1.0);
    const double z = (biased - t.near) * t.depth_scale;
    const int slice = z >= double(slices) ? slices : (z > 0.0 ? int(z) : 0);
    const int64_t per_face = int64_t(res) * res * (slices / 32);
    const VoxelGridView grid{words.data + face * per_face, res, res, slices};
    return grid.count_below(x, y, slice);
  }
};

}  // namespace dv
