// What makes pictures a user would trust: the tone curves, exposure and sRGB bytes of 8-bit
// output (the display encoding that PNG writing and the viewer share), the
// KHR_lights_punctual cone falloff and range window, and the default staging of scenes that
// bring no camera or lights (three-quarter view, key light above and beside it, ground plane).
#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cmath>
#include <random>
#include <vector>

#include "engine/raster/camera_rays.h"
#include "engine/raster/light_faces.h"
#include "engine/scene/default_staging.h"
#include "render/frame/raster_render.h"
#include "render/frame/shading.h"
#include "render/io/display_encoding.h"
#include "render/io/image.h"
#include "render/io/tone_mapping.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/support/scene_builder.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

using test::SceneBuilder;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(ToneCurves, StartAtZeroAreMonotoneAndHitKnownValues) {
  for (ToneCurve curve : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces}) {
    EXPECT_EQ(apply_tone_curve(curve, 0.0), 0.0) << to_string(curve);
    EXPECT_EQ(apply_tone_curve(curve, -1.0), 0.0) << to_string(curve);
    double previous = 0.0;
    for (double x = 0.001; x < 100.0; x *= 1.05) {
      const double y = apply_tone_curve(curve, x);
      EXPECT_GE(y, previous) << to_string(curve) << " at " << x;
      previous = y;
    }
  }
  EXPECT_DOUBLE_EQ(apply_tone_curve(ToneCurve::none, 2.5), 2.5);  // the encoder clamps
  EXPECT_DOUBLE_EQ(apply_tone_curve(ToneCurve::reinhard, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(apply_tone_curve(ToneCurve::reinhard, 3.0), 0.75);
  EXPECT_NEAR(apply_tone_curve(ToneCurve::aces, 1.0), 2.54 / 3.16, 1e-15);
  EXPECT_NEAR(apply_tone_curve(ToneCurve::aces, 0.18),
              0.18 * (2.51 * 0.18 + 0.03) / (0.18 * (2.43 * 0.18 + 0.59) + 0.14), 1e-15);
  EXPECT_EQ(apply_tone_curve(ToneCurve::aces, 1000.0), 1.0);
  EXPECT_LT(apply_tone_curve(ToneCurve::reinhard, 1000.0), 1.0);
  EXPECT_EQ(parse_tone_curve("aces"), ToneCurve::aces);
  EXPECT_THROW(parse_tone_curve("filmic"), InputError);
}

TEST(Exposure, PlusOneEvDoublesLinearValues) {
  Image linear(2, 1);
  linear.rgb = {0.0f, 0.1f, 0.25f, 0.5f, 1.0f, 3.0f};
  const Image same = apply_display_transform(linear, {});
  EXPECT_EQ(same.rgb, linear.rgb);
  const Image doubled = apply_display_transform(linear, {1.0, ToneCurve::none});
  for (size_t i = 0; i < linear.rgb.size(); ++i)
    EXPECT_EQ(doubled.rgb[i], 2.0f * linear.rgb[i]) << i;
  const Image halved_then_mapped = apply_display_transform(linear, {-1.0, ToneCurve::reinhard});
  EXPECT_FLOAT_EQ(halved_then_mapped.rgb[4], float(0.5 / 1.5));
}

// A spot light at the origin shining along -y; the point at `angle_deg` from the axis, 2 away.
double spot_arrival(const Light& light, double angle_deg) {
  const LightView view = make_light_view(light);
  const dvec3 p = 2.0 * dvec3(std::sin(angle_deg * kDeg), -std::cos(angle_deg * kDeg), 0.0);
  return light_arrival(view, p).intensity;
}

TEST(DisplayEncoding, BytesEqualRenderPngBytes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-0.1f, 1.5f);
  std::vector<float> samples = {0.0f, -0.0f, 1.0f, 0.0031308f, 2.0f, -1.0f};
  for (int i = 0; i < 200000; ++i) samples.push_back(value(rng));
  for (const DisplayTransform transform :
       {DisplayTransform{}, DisplayTransform{1.5, ToneCurve::none},
        DisplayTransform{-0.5, ToneCurve::reinhard}, DisplayTransform{0.0, ToneCurve::aces}}) {
    const DisplayEncoding encoding = make_display_encoding(transform);
    for (int b = 0; b < 255; ++b) {  // the thresholds themselves and their neighbours
      const float at = encoding.thresholds[b];
      samples.push_back(at);
      samples.push_back(std::nextafter(at, 0.0f));
    }
    Image linear(int(samples.size() + 2) / 3, 1);
    for (size_t i = 0; i < samples.size(); ++i) linear.rgb[i] = samples[i];
    const Image shown = apply_display_transform(linear, transform);
    int wrong = 0;
    for (size_t i = 0; i < linear.rgb.size(); ++i)
      wrong += encoding.byte(linear.rgb[i]) != srgb_byte(shown.rgb[i]);
    EXPECT_EQ(wrong, 0) << to_string(transform.curve) << " " << transform.exposure_ev;
  }
}

TEST(DisplayEncoding, PngFilesHoldSrgbBytesOfTheShownValues) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-0.2f, 1.7f);
  Image linear(97, 61);
  for (float& v : linear.rgb) v = value(rng);
  linear.rgb[0] = 0.0031308f;
  linear.rgb[1] = 1.0f;
  for (const DisplayTransform transform :
       {DisplayTransform{}, DisplayTransform{0.7, ToneCurve::reinhard},
        DisplayTransform{-1.0, ToneCurve::aces}}) {
    const std::string path = (test::scratch_dir("render_scratch") / "encoded.png").string();
    write_image(path, linear, transform);
    int width = 0, height = 0, channels = 0;
    unsigned char* read = stbi_load(path.c_str(), &width, &height, &channels, 3);
    ASSERT_NE(read, nullptr) << path;
    ASSERT_EQ(width, linear.width);
    ASSERT_EQ(height, linear.height);
    const Image shown = apply_display_transform(linear, transform);
    int wrong = 0;
    for (size_t i = 0; i < shown.rgb.size(); ++i) wrong += read[i] != srgb_byte(shown.rgb[i]);
    stbi_image_free(read);
    EXPECT_EQ(wrong, 0) << to_string(transform.curve) << " " << transform.exposure_ev;
  }
}

TEST(GltfLights, SpotConeFallsOffAsTheSpecSays) {
  Light spot;
  spot.type = LightType::spot;
  spot.direction = {0.0, -1.0, 0.0};
  spot.cutoff_deg = 30.0;    // outerConeAngle
  spot.penumbra_deg = 10.0;  // inner = 20 degrees
  spot.intensity = 8.0;
  spot.gltf_cone = true;
  // The spec: t = clamp((cos a - cos outer) / (cos inner - cos outer), 0, 1), attenuation t^2.
  for (double a : {0.0, 15.0, 20.0, 22.0, 25.0, 28.0, 29.9, 30.5}) {
    const double t = std::clamp((std::cos(a * kDeg) - std::cos(30.0 * kDeg)) /
                                    (std::cos(20.0 * kDeg) - std::cos(30.0 * kDeg)),
                                0.0, 1.0);
    EXPECT_NEAR(spot_arrival(spot, a), 8.0 / 4.0 * t * t, 1e-12) << a;
  }
  spot.gltf_cone = false;  // deepvox's smoothstep penumbra is unchanged
  const double x = (std::cos(25.0 * kDeg) - std::cos(30.0 * kDeg)) /
                   (std::cos(20.0 * kDeg) - std::cos(30.0 * kDeg));
  EXPECT_NEAR(spot_arrival(spot, 25.0), 2.0 * x * x * (3.0 - 2.0 * x), 1e-12);
}

TEST(GltfLights, RangeWindowAsTheSpecRecommends) {
  Light omni;
  omni.type = LightType::omni;
  omni.intensity = 5.0;
  omni.range = 2.0;
  const LightView view = make_light_view(omni);
  for (double d : {0.5, 1.0, 1.9, 2.0, 3.0}) {
    const double window = std::clamp(1.0 - std::pow(d / 2.0, 4.0), 0.0, 1.0);
    EXPECT_NEAR(light_arrival(view, {d, 0.0, 0.0}).intensity, 5.0 * window / (d * d), 1e-12) << d;
  }
  omni.range = 0.0;  // no range: plain inverse square
  EXPECT_DOUBLE_EQ(light_arrival(make_light_view(omni), {3.0, 0.0, 0.0}).intensity, 5.0 / 9.0);
}

// Whether world point p lies inside the camera's image (in front, within both half-angles).
bool in_view(const Camera& cam, const dvec3& p) {
  const CameraView v = make_camera_view(cam);
  const dvec3 d = p - cam.position;
  const double z = glm::dot(d, v.forward);
  if (z <= cam.near_plane) return false;
  const double sx = glm::dot(d, glm::normalize(v.right)) / (z * glm::length(v.right));
  const double sy = glm::dot(d, glm::normalize(v.up)) / (z * glm::length(v.up));
  return std::abs(sx) <= 1.0 && std::abs(sy) <= 1.0;
}

std::vector<dvec3> corners(const Aabb& b) {
  std::vector<dvec3> out;
  for (int i = 0; i < 8; ++i)
    out.push_back({i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z});
  return out;
}

TEST(DefaultStaging, ThreeQuarterViewSeesTheWholeBounds) {
  for (const Aabb& box : {Aabb{dvec3(-1.0), dvec3(1.0)}, Aabb{{4, 0, -1}, {5, 3, 0}},
                          Aabb{{0, 0, 0}, {10, 0.2, 0.5}}}) {
    const Camera cam = default_camera(box);
    for (const dvec3& c : corners(box)) EXPECT_TRUE(in_view(cam, c)) << c.x << "," << c.y;
    const dvec3 view = glm::normalize(cam.position - box.center());
    EXPECT_GT(view.y, 0.3);            // from above
    EXPECT_GT(std::abs(view.x), 0.3);  // and from the side: not head-on
    EXPECT_GT(view.z, 0.3);            // the front (+z) stays in sight
    EXPECT_EQ(cam.target, box.center());
  }
}

TEST(DefaultStaging, KeyLightIsAboveAndBesideTheCameraAndCoversTheBounds) {
  const Aabb box{{4, 0, -1}, {5, 3, 0}};
  const Camera cam = default_camera(box);
  const std::vector<Light> lights = default_lights(box, cam);
  ASSERT_EQ(lights.size(), 2u);
  const Light& key = lights[0];
  ASSERT_EQ(key.type, LightType::spot);
  EXPECT_GT(key.position.y, box.hi.y);  // above
  const dvec3 to_key = glm::normalize(key.position - box.center());
  const dvec3 to_cam = glm::normalize(cam.position - box.center());
  EXPECT_GT(to_key.y, to_cam.y);  // higher than the camera
  const double apart = std::acos(glm::dot(glm::normalize(dvec3(to_key.x, 0, to_key.z)),
                                          glm::normalize(dvec3(to_cam.x, 0, to_cam.z))));
  EXPECT_NEAR(apart / kDeg, 60.0, 1e-9);  // beside the camera
  const LightView view = make_light_view(key);
  for (const dvec3& c : corners(box))  // the whole model in the cone's full-intensity core
    EXPECT_GE(glm::dot(glm::normalize(c - key.position), view.direction), view.cos_inner);
  EXPECT_NEAR(light_arrival(view, box.center()).intensity, 1.0, 1e-12);
  EXPECT_EQ(lights[1].type, LightType::directional);  // fill from the camera's side
  EXPECT_GT(glm::dot(-lights[1].direction, to_cam), 0.999);
}

// Texels of the key light's map (1024 x 1024, the shadow map's default) across the model: the
// smaller of the extents of its projected corners along the map's two axes.
double key_map_texels_across(const Light& key, const Aabb& model, const Aabb& casters) {
  constexpr int kRes = 1024;
  const std::vector<ShadowFace> faces =
      light_map_faces(make_light_view(key), casters, glm::length(casters.extent()), kRes);
  EXPECT_EQ(faces.size(), 1u);
  double lo_u = 1e30, hi_u = -1e30, lo_v = 1e30, hi_v = -1e30;
  for (const dvec3& c : corners(model)) {
    FacePoint p;
    EXPECT_TRUE(project_to_face(faces[0], kRes, c, p));
    EXPECT_TRUE(p.u >= 0.0 && p.u <= kRes - 1 && p.v >= 0.0 && p.v <= kRes - 1);  // on the map
    lo_u = std::min(lo_u, p.u), hi_u = std::max(hi_u, p.u);
    lo_v = std::min(lo_v, p.v), hi_v = std::max(hi_v, p.v);
  }
  return std::min(hi_u - lo_u, hi_v - lo_v);
}

TEST(DefaultStaging, KeyConeSpendsItsMapOnTheCastersAndTheirShadow) {
  // Before the cone was fitted it reached 2.5 radii around the model whether or not there was a
  // ground (44 degrees): 231 texels across the cube, 130 across the tall box's narrow side.
  struct Case {
    Aabb box;
    double without_ground, with_ground;  // texels across at least
  };
  for (const Case& c : {Case{{{-0.5, 0, -0.5}, {0.5, 1, 0.5}}, 700.0, 550.0},
                        Case{{{4, 0, -1}, {5, 3, 0}}, 400.0, 300.0}}) {
    SceneBuilder b;
    b.add(make_box(c.box.lo, c.box.hi));
    b.scene.camera = default_camera(c.box);
    Scene bare = b.scene;
    ASSERT_TRUE(stage_scene(bare, {.ground = GroundPlane::off}));
    ASSERT_EQ(bare.objects.size(), 1u);
    EXPECT_GT(key_map_texels_across(bare.lights[0], c.box, c.box), c.without_ground);
    ASSERT_TRUE(stage_scene(b.scene, {}));
    ASSERT_EQ(b.scene.objects.size(), 2u);
    EXPECT_GT(key_map_texels_across(b.scene.lights[0], c.box, world_bounds(b.scene)),
              c.with_ground);
    // The ground's cone is wider: it also lights the model's shadow on the ground (checked by
    // the next tests), so its map spends fewer texels on the model.
    EXPECT_GT(b.scene.lights[0].cutoff_deg, bare.lights[0].cutoff_deg);
  }
}

TEST(DefaultStaging, StagedLightsStandOnTheCamerasSide) {
  const Aabb box{{-0.5, 0, -0.5}, {0.5, 1, 0.5}};
  for (double azimuth : {35.0, 180.0, -120.0}) {  // default view, from behind, from the left
    Camera cam = default_camera(box);
    const dvec3 offset = cam.position - cam.target;
    const double a = azimuth * kDeg, horizontal = std::hypot(offset.x, offset.z);
    cam.position = cam.target + dvec3(horizontal * std::sin(a), offset.y, horizontal * std::cos(a));
    const std::vector<Light> lights = default_lights(box, cam);
    const dvec3 to_key = lights[0].position - box.center();
    const dvec3 to_cam = cam.position - box.center();
    // Horizontally 60 degrees round from the camera: on its side of the model.
    const double cos_apart = glm::dot(glm::normalize(dvec3(to_key.x, 0, to_key.z)),
                                      glm::normalize(dvec3(to_cam.x, 0, to_cam.z)));
    EXPECT_NEAR(cos_apart, 0.5, 1e-9) << azimuth;
    EXPECT_GT(
        glm::dot(glm::normalize(lights[1].direction), glm::normalize(cam.target - cam.position)),
        0.999999)
        << azimuth;  // the fill shines along the view
  }
}

TEST(DefaultStaging, GroundPlaneLiesBelowTheBoundsAndCatchesTheKeyLightsShadow) {
  SceneBuilder b;
  b.add(make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}));
  const Aabb box = world_bounds(b.scene);
  b.scene.camera = default_camera(box);
  EXPECT_TRUE(stage_scene(b.scene, {}));
  EXPECT_FALSE(add_ground_plane(b.scene));  // once only
  ASSERT_EQ(b.scene.objects.size(), 2u);
  const Object& ground = b.scene.objects[1];
  EXPECT_EQ(ground.name, "ground");
  const Aabb ground_box = world_bounds(b.scene);
  // kGroundGapRadii of the bounding-sphere radius below: 0.0087 for the unit box.
  const double radius = 0.5 * glm::length(box.extent());
  for (const dvec3& v : b.scene.meshes[ground.mesh].positions) {
    EXPECT_LT(v.y, box.lo.y);
    EXPECT_NEAR(v.y, box.lo.y - kGroundGapRadii * radius, 1e-12);
  }
  EXPECT_LT(ground_box.lo.x, box.lo.x - 2.0);
  EXPECT_GT(ground_box.hi.z, box.hi.z + 2.0);
  const SceneData data = b.build();
  // The key light's ray through the box's centre and through its far top edge meet the ground
  // in the box's shadow: points the camera sees and the cone lights at full intensity.
  const Light& key = b.scene.lights[0];
  const LightView& key_view = data.view().lights[0];
  const double y = b.scene.meshes[ground.mesh].positions[0].y;
  const dvec3 through = glm::normalize(box.center() - key.position);
  const dvec3 away = glm::normalize(dvec3(through.x, 0.0, through.z));
  for (const dvec3& caster : {box.center(), box.center() + dvec3(0, 0.5, 0) + 0.45 * away}) {
    const dvec3 ray = glm::normalize(caster - key.position);
    const dvec3 shadowed = key.position + ray * ((y - key.position.y) / ray.y);
    EXPECT_EQ(test::oracle_at(data, 0, shadowed), 0.0);
    EXPECT_NEAR(light_arrival(key_view, shadowed).intensity *
                    glm::dot(shadowed - key.position, shadowed - key.position) / key.intensity,
                1.0, 1e-12);  // in the cone's core
    EXPECT_TRUE(in_view(b.scene.camera, shadowed));
  }
  // Ground on the light's side of the box, just beyond it, is lit.
  const dvec3 lit = dvec3(box.center().x, y, box.center().z) - 0.6 * away;
  EXPECT_EQ(test::oracle_at(data, 0, lit), 1.0);
  EXPECT_GT(light_arrival(key_view, lit).intensity, 0.5);
  // Without a ground there is nothing to cast the shadow on.
  SceneBuilder bare;
  bare.add(make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}));
  bare.scene.camera = b.scene.camera;
  EXPECT_TRUE(stage_scene(bare.scene, {.ground = GroundPlane::off}));
  EXPECT_EQ(bare.scene.objects.size(), 1u);
  // A scene with its own lights gets a ground only when asked.
  Scene lit_scene = bare.scene;
  EXPECT_FALSE(stage_scene(lit_scene, {}));
  EXPECT_EQ(lit_scene.objects.size(), 1u);
  EXPECT_FALSE(stage_scene(lit_scene, {.ground = GroundPlane::on}));
  EXPECT_EQ(lit_scene.objects.size(), 2u);
  EXPECT_EQ(lit_scene.lights.size(), 2u);  // the lights staged before, untouched
}

TEST(DefaultStaging, WhiteModelUnderTheStagedKeyKeepsItsShadingThroughTheDefaultToneCurve) {
  SceneBuilder b;
  Object& model = b.add(make_icosphere(0.5, 3));
  model.material.color = dvec3(1.0);  // glTF's default white, glossy (roughness 0)
  model.material.specular = 0.24;
  model.material.shininess = 512.0;
  b.scene.camera = default_camera(world_bounds(b.scene));
  b.scene.camera.width = 160;
  b.scene.camera.height = 120;
  ASSERT_TRUE(stage_scene(b.scene, {}));
  const SceneData data = b.build();
  auto method = shadow_registry().create("shadowmap");
  const Image linear =
      render_raster(Backend::cpu, data, b.scene.camera, *method, b.scene.background).render.image;
  const auto white_channels = [&](ToneCurve curve) {
    int n = 0;
    for (unsigned char byte : srgb_bytes(linear, {0.0, curve})) n += byte == 255;
    return n;
  };
  EXPECT_EQ(white_channels(kDefaultToneCurve), 0);
  EXPECT_GT(white_channels(ToneCurve::none), 300);  // what the old default clipped
  // The linear values (an EXR's) are the renderer's, untouched by any curve.
  float brightest = 0.0f;
  for (float v : linear.rgb) brightest = std::max(brightest, v);
  EXPECT_GT(brightest, 1.0f);
}

}  // namespace
}  // namespace dv
