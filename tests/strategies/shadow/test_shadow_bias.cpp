// Shadow bias and self-shadowing, on analytic stand-ins for the Khronos scenes:
// a backdrop lit at a grazing angle behind tinted slabs and an opaque block (acne of the map
// methods at their defaults against the exact reference image), the receiver bias against its
// formula and what it lets leak behind a thin card at contact, a constant-extinction cube under
// a spot light (no surface bias inside media), and a draped cloth (rasterized and ray traced
// reference images agree away from silhouettes: no self-shadowing speckles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "engine/raster/camera_rays.h"
#include "engine/raster/light_faces.h"
#include "engine/scene/ray_query.h"
#include "render/frame/raster_render.h"
#include "render/frame/reference_render.h"
#include "render/io/image.h"
#include "strategies/shadow/probe.h"
#include "tests/support/scene_builder.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

using test::SceneBuilder;

// Whether two linear colours differ by more than `levels` of 255 in some sRGB byte, as the
// PNG writer quantises them.
bool differs(const dvec3& a, const dvec3& b, int levels) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(srgb_byte(float(a[c]))) - int(srgb_byte(float(b[c])))) > levels) return true;
  return false;
}

double fraction_differing(const Image& a, const Image& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) n += differs(a.at(x, y), b.at(x, y), 8);
  return double(n) / (double(a.width) * a.height);
}

// AttenuationTest-like: a 6 x 6 floor lit by a spot light 0.55 above it from x = -3.2, so the
// light meets the floor 76 to 84 degrees from its normal where the camera looks; a row of
// tinted slabs (translucent or opaque) and an opaque block stand on it.
SceneBuilder grazing_backdrop(bool translucent) {
  SceneBuilder b;
  Object& floor = b.add(make_box({-3, -0.05, -3}, {3, 0, 3}));
  floor.material = {dvec3(0.85), 0.05, 0.9, 0.0, 1.0, 1.0};
  const dvec3 tints[] = {{0.9, 0.3, 0.3}, {0.3, 0.9, 0.3}, {0.3, 0.4, 0.95}, {0.95, 0.85, 0.3}};
  for (int i = 0; i < 4; ++i) {
    const double z = -1.2 + 0.6 * i;
    Object& slab = b.add(make_box({-1.6, 0.0, z}, {-1.55, 0.25, z + 0.4}));
    slab.material = {tints[i], 0.05, 0.8, 0.0, 1.0, translucent ? 0.25 + 0.15 * i : 1.0};
  }
  Object& block = b.add(make_box({-0.9, 0.0, 1.3}, {-0.6, 0.25, 1.6}));
  block.material = {dvec3(0.6, 0.6, 0.6), 0.05, 0.8, 0.0, 1.0, 1.0};
  Light& l = b.spot({-3.2, 0.55, 0.0}, glm::normalize(dvec3(1.0, -0.12, 0.0)), 40.0);
  l.intensity = 60.0;
  b.scene.camera.position = {0.4, 3.0, 2.6};
  b.scene.camera.target = {0.2, 0.0, 0.0};
  b.scene.camera.fov_deg = 55.0;
  b.scene.camera.width = 96;
  b.scene.camera.height = 72;
  return b;
}

// Fraction of pixels more than 8/255 off the reference image.
double acne_fraction(bool translucent, const std::string& method, const std::string& params) {
  SceneBuilder b = grazing_backdrop(translucent);
  const SceneData data = b.build();
  auto reference = shadow_registry().create("reference");
  auto approx = test::make_shadow_method(method, params);
  const Camera& cam = b.scene.camera;
  const Image exact = render_raster(Backend::cpu, data, cam, *reference, dvec3(0.0)).render.image;
  const Image got = render_raster(Backend::cpu, data, cam, *approx, dvec3(0.0)).render.image;
  return fraction_differing(exact, got);
}

double reported_fraction(bool translucent, const std::string& method, const std::string& params) {
  const double f = acne_fraction(translucent, method, params);
  std::cout << method << " '" << params << "' on " << (translucent ? "translucent" : "opaque")
            << " slabs: fraction of pixels > 8/255 off the reference " << f << "\n";
  ::testing::Test::RecordProperty(method + (translucent ? "_translucent" : "_opaque"),
                                  std::to_string(f));
  return f;
}

// Every map method at its default parameters, opaque casters (the shadowmap method's domain).
TEST(ShadowBias, GrazingBackdropIsCleanAtDefaults) {
  EXPECT_LE(reported_fraction(false, "shadowmap", ""), 0.01);
  EXPECT_LE(reported_fraction(false, "dsm", ""), 0.01);
  EXPECT_LE(reported_fraction(false, "transmittance-slicemap", ""), 0.01);
}

// Translucent casters, DSM at its defaults (bias and eps 0.02: a visibility error within 0.02
// stays under 8/255 of the light; eps 0.05 alone moved 4.5% of these pixels by more). (The
// transmittance slicemap is left out: a slab's two faces share a slice and count once, which
// no bias changes.)
TEST(ShadowBias, GrazingBackdropBehindTranslucentSlabsIsClean) {
  EXPECT_LE(reported_fraction(true, "dsm", ""), 0.01);
}

// The bias helper itself: surface receivers get the constant plus slope x reach x texel x
// tan(theta), capped at kMaxBiasTangent; receivers not on a surface get none.
TEST(ShadowBias, ReceiverDepthFollowsTheAngleToTheLight) {
  SceneBuilder b;
  b.add(make_box({-1, -0.1, -1}, {1, 0, 1}));
  b.spot({0.0, 2.0, 0.0}, {0.0, -1.0, 0.0}, 40.0);
  const SceneData data = b.build();
  const ShadowFace f =
      light_map_faces(data.view().lights[0], data.view().bounds, data.view().diagonal, 256)[0];
  const dvec3 p(0.0, 0.0, 0.0);
  const double depth = shadow_depth(f, p), texel = depth * f.texel_size;
  EXPECT_EQ(receiver_depth(f, ShadowReceiver{p}, depth, 0.01, 2.0, 1.5), depth);
  for (double deg : {0.0, 45.0, 80.0, 85.0, 89.0}) {
    const double a = deg * 3.14159265358979323846 / 180.0;
    const ShadowReceiver r{p, dvec3(std::sin(a), std::cos(a), 0.0)};
    const double tangent = std::min(std::tan(a), kMaxBiasTangent);
    EXPECT_NEAR(depth - receiver_depth(f, r, depth, 0.01, 2.0, 1.5),
                0.01 + 2.0 * 1.5 * texel * tangent, 1e-12)
        << deg;
  }
}

// What the receiver bias lets leak at a contact shadow: behind a 2 mm opaque card standing on
// the grazing-lit floor (81.5 degrees from the normal at the card), floor points closer to the
// card along the light's ray than their own bias are lit; none farther than that (plus the
// card's own depth change over the filter's reach, a texel at most) is.
struct Leak {
  double distance = 0.0;  // farthest leaking point's distance to the card along the light ray
  double bias = 0.0;      // that point's bias
  int points = 0;
};

Leak contact_leak(const std::string& method, double slope, double reach) {
  SceneBuilder b = grazing_backdrop(false);
  b.scene.objects.resize(1);
  b.add(make_box({0.5, 0.0, -0.2}, {0.502, 0.25, 0.2}));
  const SceneData data = b.build();
  const SceneView& s = data.view();
  const LightView& light = s.lights[0];
  const ShadowFace face = light_map_faces(light, s.bounds, s.diagonal, 1024)[0];
  std::vector<dvec3> points;
  for (int i = 0; i < 400; ++i) points.push_back({0.5021 + 0.0005 * i, 0.0, 0.0});
  auto reference = shadow_registry().create("reference");
  auto approx = test::make_shadow_method(method, "");
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  const ProbeResults got = probe_transmittance(Backend::cpu, data, *approx, points);
  Leak leak;
  for (size_t i = 0; i < points.size(); ++i) {
    const dvec3& p = points[i];
    const double depth = shadow_depth(face, p);
    const double bias = depth - receiver_depth(face, ShadowReceiver{p, dvec3(0.0, 1.0, 0.0)}, depth,
                                               1e-4 * s.diagonal, slope, reach);
    const double to_card = (p.x - 0.5) * depth / (p.x - light.position.x);
    EXPECT_LT(exact.transmittance[i], 0.5) << i;
    if (got.transmittance[i] < 0.5) continue;
    EXPECT_LE(to_card, bias + reach * depth * face.texel_size) << method << " lit at " << p.x;
    if (to_card > leak.distance) leak = {to_card, bias, leak.points};
    ++leak.points;
  }
  std::cout << method << ": lit behind the card up to " << leak.distance
            << " along the light ray (bias there " << leak.bias << "), " << leak.points
            << " of 400 floor points 0.5 mm apart\n";
  ::testing::Test::RecordProperty(method + "_leak", std::to_string(leak.distance));
  return leak;
}

TEST(ShadowBias, ContactShadowsLeakOnlyWithinTheBias) {
  EXPECT_GT(contact_leak("shadowmap", 1.5, 1.5).points, 0);  // defaults: slope 1.5, pcf 2
  EXPECT_GT(contact_leak("dsm", 3.0, 0.5).points, 0);        // defaults: slope 3, nearest texel
}

// A constant-extinction cube (no surface opacity) under a spot light: inside it every point is
// a medium point, and the dsm lookup must not be biased as if it were a surface.
struct MediumError {
  double mean, max;
};

MediumError dsm_error_in_cube(const std::string& params) {
  SceneBuilder b;
  b.add(make_box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}), 0.0, InteriorKind::constant, 1.5);
  b.spot({0.3, 3.0, 0.2}, glm::normalize(dvec3(-0.3, -3.0, -0.2)), 30.0);
  const SceneData data = b.build();
  std::vector<dvec3> points;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 7; ++k) points.push_back(dvec3(i, j, k) * (0.9 / 6.0) - dvec3(0.45));
  auto reference = shadow_registry().create("reference");
  auto dsm = test::make_shadow_method("dsm", params);
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  const ProbeResults approx = probe_transmittance(Backend::cpu, data, *dsm, points);
  MediumError e{0.0, 0.0};
  for (size_t i = 0; i < points.size(); ++i) {
    const double d = std::abs(approx.transmittance[i] - exact.transmittance[i]);
    e.mean += d / double(points.size());
    e.max = std::max(e.max, d);
  }
  std::cout << "dsm " << params << " inside the cube: mean error " << e.mean << ", max " << e.max
            << "\n";
  return e;
}

TEST(ShadowBias, NoSurfaceBiasInsideMedia) {
  const MediumError exact_maps = dsm_error_in_cube("eps=0");
  EXPECT_LT(exact_maps.mean, 1e-3);
  EXPECT_LT(exact_maps.max, 2e-3);
  const MediumError bounded = dsm_error_in_cube("eps=0.01");
  EXPECT_LE(bounded.max, 0.01 + 1e-3);
}

// A draped cloth: a 64 x 64-cell sheet bent in two directions over a floor, lit from the side.
TriangleMesh draped_cloth() {
  TriangleMesh m;
  m.name = "draped cloth";
  const int n = 64;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1.0 + 2.0 * i / n, z = -1.0 + 2.0 * j / n;
      m.positions.push_back({x, 0.6 + 0.25 * std::sin(2.2 * x) * std::cos(1.7 * z), z});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t v = uint32_t(j * (n + 1) + i);
      m.triangles.push_back({v, v + uint32_t(n + 1), v + 1});
      m.triangles.push_back({v + 1, v + uint32_t(n + 1), v + uint32_t(n + 2)});
    }
  return m;
}

// Front object per pixel of the camera (-1: background), from the BVH.
std::vector<int> front_objects(const SceneData& data, const Camera& camera) {
  const CameraView cam = make_camera_view(camera);
  std::vector<int> ids(size_t(cam.width) * cam.height, -1);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      RayHit h{};
      const ShearedRay ray = make_sheared_ray(cam.position, camera_ray_direction(cam, x, y));
      if (next_hit(data.view(), ray, 0.0, -1, 1e300, h))
        ids[size_t(y) * cam.width + x] = int(data.view().triangle_object[h.triangle]);
    }
  return ids;
}

// Silhouette pixels: those whose 3 x 3 neighbourhood holds another front object or background.
bool on_silhouette(const std::vector<int>& ids, int width, int height, int x, int y) {
  const int own = ids[size_t(y) * width + x];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= width || v >= height) continue;
      if (ids[size_t(v) * width + u] != own) return true;
    }
  return false;
}

TEST(ShadowBias, RasterAndRayTracedReferenceAgreeAwayFromSilhouettes) {
  SceneBuilder b;
  Object& floor = b.add(make_box({-2, -0.05, -2}, {2, 0, 2}));
  floor.material = {dvec3(0.8), 0.05, 0.9, 0.0, 1.0, 1.0};
  Object& cloth = b.add(draped_cloth());
  cloth.material = {dvec3(0.9, 0.8, 0.6), 0.05, 0.9, 0.0, 1.0, 1.0};
  Light& l = b.spot({-1.5, 3.0, 0.8}, glm::normalize(dvec3(1.5, -2.4, -0.8)), 45.0);
  l.intensity = 12.0;
  Camera& cam = b.scene.camera;
  cam.position = {0.3, 2.6, 2.8};
  cam.target = {0.0, 0.4, 0.0};
  cam.fov_deg = 50.0;
  cam.width = 160;
  cam.height = 120;
  const SceneData data = b.build();
  auto reference = shadow_registry().create("reference");
  const Image raster = render_raster(Backend::cpu, data, cam, *reference, dvec3(0.0)).render.image;
  const Image traced = render_reference(Backend::cpu, data, cam, *reference, dvec3(0.0)).image;
  const std::vector<int> ids = front_objects(data, cam);
  int interior = 0, speckles = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      if (on_silhouette(ids, cam.width, cam.height, x, y)) continue;
      ++interior;
      speckles += differs(raster.at(x, y), traced.at(x, y), 8);
    }
  std::cout << "raster vs ray traced reference: " << speckles << " of " << interior
            << " pixels away from silhouettes differ by more than 8/255\n";
  EXPECT_GT(interior, cam.width * cam.height / 2);
  EXPECT_EQ(speckles, 0);
}

}  // namespace
}  // namespace dv
