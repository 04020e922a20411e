// What a surface looks like at one point of one triangle, for host and device: the base-colour
// texture sampled with its sampler (wrap modes, nearest or bilinear filtering of the decoded
// linear texels) at the point's interpolated texture coordinates, the coverage its alpha gives
// (glTF alphaMode: MASK cuts at alphaCutoff, BLEND is partial), and the interpolated vertex
// normal. Untextured objects keep their material's constants, untouched, so scenes without
// textures render bit for bit as before. Every step is plain double arithmetic (no library
// transcendental, no fused multiply-add), so host and device decide coverage identically.
#pragma once

#include <cmath>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene_view.h"

namespace dv {

// Barycentric weights of p (in or near the plane of triangle a, b, c); a's corner for a
// degenerate triangle.
DV_HD inline dvec3 barycentric_weights(const dvec3& p, const dvec3& a, const dvec3& b,
                                       const dvec3& c) {
  const dvec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
  const double d20 = glm::dot(d, e0), d21 = glm::dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0.0)) return dvec3(1.0, 0.0, 0.0);
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return dvec3(1.0 - v - w, v, w);
}

DV_HD inline dvec3 triangle_weights(const SceneView& s, uint32_t tri, const dvec3& p) {
  const u32vec3 idx = s.triangles[tri];
  return barycentric_weights(p, s.vertices[idx.x], s.vertices[idx.y], s.vertices[idx.z]);
}

// Texel index i of a texture n texels wide under a wrap mode.
DV_HD inline int wrap_texel(int i, int n, TextureWrap mode) {
  if (mode == TextureWrap::clamp) return clamp_value(i, 0, n - 1);
  if (mode == TextureWrap::repeat) {
    const int m = i % n;
    return m < 0 ? m + n : m;
  }
  int m = i % (2 * n);
  if (m < 0) m += 2 * n;
  return m < n ? m : 2 * n - 1 - m;
}

// Linear RGB and alpha of texel (x, y) (already wrapped).
DV_HD inline dvec4 fetch_texel(const SceneView& s, const TextureView& t, int x, int y) {
  const int64_t at = t.offset + (int64_t(y) * t.width + x) * 4;
  return dvec4(s.srgb_to_linear[s.texels[at]], s.srgb_to_linear[s.texels[at + 1]],
               s.srgb_to_linear[s.texels[at + 2]], double(s.texels[at + 3]) / 255.0);
}

// floor(x) as an int, x first limited to where it fits (far-off UVs wrap like nearby ones
// only up to this range, which no real asset reaches).
DV_HD inline int floor_to_int(double x) {
  return int(floor(clamp_value(x, -1e9, 1e9)));
}

// The texture's linear RGBA at uv (glTF: u right, v down from the image's top row).
DV_HD inline dvec4 sample_texture(const SceneView& s, const TextureView& t, const dvec2& uv) {
  const double x = uv.x * double(t.width), y = uv.y * double(t.height);
  if (t.filter == TextureFilter::nearest)
    return fetch_texel(s, t, wrap_texel(floor_to_int(x), t.width, t.wrap_s),
                       wrap_texel(floor_to_int(y), t.height, t.wrap_t));
  const double cx = x - 0.5, cy = y - 0.5;
  const int x0 = floor_to_int(cx), y0 = floor_to_int(cy);
  const double fx = cx - double(x0), fy = cy - double(y0);
  const int xa = wrap_texel(x0, t.width, t.wrap_s), xb = wrap_texel(x0 + 1, t.width, t.wrap_s);
  const int ya = wrap_texel(y0, t.height, t.wrap_t), yb = wrap_texel(y0 + 1, t.height, t.wrap_t);
  const dvec4 top = fetch_texel(s, t, xa, ya) * (1.0 - fx) + fetch_texel(s, t, xb, ya) * fx;
  const dvec4 bottom = fetch_texel(s, t, xa, yb) * (1.0 - fx) + fetch_texel(s, t, xb, yb) * fx;
  return top * (1.0 - fy) + bottom * fy;
}

// Coverage of a point whose texel alpha is `texel_alpha` (glTF alphaMode).
DV_HD inline double texture_coverage(const ObjectView& o, double texel_alpha) {
  const double a = o.coverage_factor * texel_alpha;
  if (o.alpha_mode == AlphaMode::mask) return a >= o.alpha_cutoff ? 1.0 : 0.0;
  return o.alpha_mode == AlphaMode::blend ? a : 1.0;
}

// A surface point's opacity per crossing, transmissive part and base colour (Material).
struct SurfaceLook {
  double alpha;
  double transmission;
  dvec3 color;
};

// The mesh's texture coordinates interpolated at point p of BVH triangle `tri`.
DV_HD inline dvec2 surface_uv(const SceneView& s, uint32_t tri, const dvec3& p) {
  const dvec3 w = triangle_weights(s, tri, p);
  return s.corner_uvs[3 * int64_t(tri)] * w.x + s.corner_uvs[3 * int64_t(tri) + 1] * w.y +
         s.corner_uvs[3 * int64_t(tri) + 2] * w.z;
}

// The look of `object` at point p of BVH triangle `tri`.
DV_HD inline SurfaceLook surface_look(const SceneView& s, const ObjectView& o, uint32_t tri,
                                      const dvec3& p) {
  if (o.texture < 0) return {o.alpha, o.transmission, o.color};
  const dvec2 mapped = dvec2(o.uv_transform * dvec3(surface_uv(s, tri, p), 1.0));
  const dvec4 texel = sample_texture(s, s.textures[o.texture], mapped);
  const double coverage = texture_coverage(o, texel.w);
  return {coverage * o.alpha, coverage * o.transmission, o.color * dvec3(texel)};
}

// The light `object` emits at point p of BVH triangle `tri` (Material::emission, times the
// emissive texture's linear RGB there).
DV_HD inline dvec3 surface_emission(const SceneView& s, const ObjectView& o, uint32_t tri,
                                    const dvec3& p) {
  if (o.emissive_texture < 0) return o.emission;
  const dvec2 mapped = dvec2(o.emissive_uv_transform * dvec3(surface_uv(s, tri, p), 1.0));
  return o.emission * dvec3(sample_texture(s, s.textures[o.emissive_texture], mapped));
}

// Opacity per crossing of BVH triangle `tri` at point p.
DV_HD inline double surface_alpha(const SceneView& s, uint32_t tri, const dvec3& p) {
  const ObjectView& o = s.objects[s.triangle_object[tri]];
  return o.texture < 0 ? o.alpha : surface_look(s, o, tri, p).alpha;
}

// Whether the object's opacity varies over its surface (a texture decides it per point).
DV_HD inline bool alpha_varies(const ObjectView& o) {
  return o.texture >= 0 && o.alpha_mode != AlphaMode::opaque && o.alpha > 0.0;
}

// The unit shading normal at p of BVH triangle `tri`: the vertex normals interpolated, turned
// to the side of `geometric` (unit), or `geometric` where the mesh has none.
DV_HD inline dvec3 shading_normal(const SceneView& s, uint32_t tri, const dvec3& p,
                                  const dvec3& geometric) {
  if (s.corner_normals.empty()) return geometric;
  const int64_t c = 3 * int64_t(tri);
  const dvec3 w = triangle_weights(s, tri, p);
  const dvec3 n =
      s.corner_normals[c] * w.x + s.corner_normals[c + 1] * w.y + s.corner_normals[c + 2] * w.z;
  const double len = glm::length(n);
  if (!(len > 0.0)) return geometric;
  return glm::dot(n, geometric) < 0.0 ? -n / len : n / len;
}

}  // namespace dv
