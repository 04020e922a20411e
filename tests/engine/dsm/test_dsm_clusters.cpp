// Clustered deep shadow maps (engine/dsm/light_clusters.h): the memory rule, Knecht's
// distance, Algorithm 4.2 on known distances and the hysteresis; the light-space perspective's
// body B (clipped hull, culling, warp; engine/dsm/lispsm.h); each cluster face holds exactly
// its cluster's objects (lookups on its texel-centre rays match the oracle of a scene of those
// objects only); clustered lookups (eq. 3.12) against the full oracle for spot, omni and
// directional lights; the papers' claim at equal memory on a sparse scene (objects far apart over a
// large floor, the camera close to one group): lower error near the camera than one map, with the
// dense case's numbers recorded; the shadow method's parameters, stats and rebuild rule; CPU/CUDA
// parity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "cuda/device_memory.h"
#include "engine/dsm/lispsm.h"
#include "render/frame/raster_render.h"
#include "strategies/shadow/probe.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/deep_shadow_maps.h"
#include "tests/engine/dsm/dsm_test_support.h"

namespace dv {
namespace {

TEST(ClusterLayout, EqualMemoryResolution) {
  EXPECT_EQ(cluster_resolution(1024, 1), 1024);
  EXPECT_EQ(cluster_resolution(1024, 4), 512);
  EXPECT_EQ(cluster_resolution(1024, 2), 724);  // 2 * 724^2 <= 1024^2 < 2 * 725^2
  EXPECT_EQ(cluster_resolution(1000, 3), 577);
}

TEST(ClusterLayout, DistanceIsTheLargerOfMinAndMaxPointDistances) {
  const NdcRect a{dvec2(0.0, 0.0), dvec2(0.2, 0.2)};
  const NdcRect b{dvec2(0.3, 0.0), dvec2(0.4, 0.6)};
  EXPECT_DOUBLE_EQ(rect_distance(a, b), std::sqrt(0.2 * 0.2 + 0.4 * 0.4));
  EXPECT_DOUBLE_EQ(rect_distance(a, a), 0.0);
}

ObjectDistances points_on_a_line(const std::vector<double>& x, const std::vector<bool>& seen) {
  ObjectDistances d;
  d.n = int(x.size());
  d.seen = seen;
  for (int i = 0; i < d.n; ++i)
    for (int j = 0; j < d.n; ++j) d.d.push_back(std::abs(x[size_t(i)] - x[size_t(j)]));
  return d;
}

TEST(ClusterLayout, Algorithm42GroupsWithinD0AndCapsTheCount) {
  const ObjectDistances d =
      points_on_a_line({0.0, 0.1, 1.0, 1.15, 3.0, 5.0}, {true, true, true, true, true, false});
  using Clusters = std::vector<std::vector<int>>;
  EXPECT_EQ(cluster_objects(d, 4, 0.5), (Clusters{{0, 1}, {2, 3}, {4}}));  // 5 unseen: no map
  EXPECT_EQ(cluster_objects(d, 2, 0.5), (Clusters{{0, 1}, {2, 3, 4}}));    // 4 to the nearest
  EXPECT_EQ(cluster_objects(d, 1, 0.5), (Clusters{{0, 1, 2, 3, 4}}));
  EXPECT_EQ(cluster_objects(d, 8, 10.0), (Clusters{{0, 1, 2, 3, 4}}));
  EXPECT_EQ(cluster_objects(points_on_a_line({2.0}, {true}), 4, 0.5), (Clusters{{0}}));
}

TEST(Lispsm, ClippedConvexHullOfACube) {
  std::vector<dvec3> cube;
  for (int c = 0; c < 8; ++c) cube.push_back(dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  // x + y <= 1 cuts the cube into a prism: 6 vertices, all on or below the plane.
  const std::vector<dvec3> prism = clipped_convex_hull(cube, {HalfSpace(-1, -1, 0, 1)});
  Aabb box;
  for (const dvec3& p : prism) {
    EXPECT_LE(p.x + p.y, 1.0 + 1e-12);
    box.extend(p);
  }
  EXPECT_EQ(box.lo, dvec3(0.0));
  EXPECT_EQ(box.hi, dvec3(1.0));
  EXPECT_TRUE(clipped_convex_hull(cube, {HalfSpace(1, 0, 0, -2)}).empty());
  // A point and a square (Algorithm 4.3's light and frustum): a pyramid cut at half height.
  const std::vector<dvec3> pyramid = clipped_convex_hull(
      {{0, 2, 0}, {-1, 0, -1}, {1, 0, -1}, {-1, 0, 1}, {1, 0, 1}}, {HalfSpace(0, -1, 0, 1)});
  Aabb top;
  for (const dvec3& p : pyramid)
    if (p.y > 0.5) top.extend(p);
  EXPECT_NEAR(top.hi.x, 0.5, 1e-12);
  EXPECT_NEAR(top.lo.z, -0.5, 1e-12);
}

// The body B holds what the camera sees lit by the face; a box behind the camera (it looks
// along -z from z = 10), outside the frustum's hull with the light, is not seen; the map plane
// spans [-1, 1] over B.
TEST(Lispsm, BodyCullsWhatTheCameraCannotSeeShadowed) {
  test::SceneBuilder b;
  b.add(make_quad(40.0));
  const LightView light = make_light_view(b.spot(dvec3(0, 20, 0), dvec3(0, -1, 0), 45.0));
  Aabb scene_bounds{dvec3(-20, -1, -20), dvec3(20, 3, 20)};
  Camera camera;
  camera.position = dvec3(0, 2, 10);
  camera.target = dvec3(0, 0, 5);
  const ShadowFace face = light_map_faces(light, scene_bounds, 60.0, 1)[0];
  const LispsmSpace s = lispsm_space(face, light, camera, scene_bounds, 60.0);
  ASSERT_FALSE(s.empty);
  EXPECT_TRUE(s.warped);
  dvec2 lo, hi;
  EXPECT_TRUE(s.box_rect(Aabb{dvec3(-0.5, 0, 4), dvec3(0.5, 1, 5)}, lo, hi));  // in view
  EXPECT_GE(lo.x, -1.0);
  EXPECT_LE(hi.y, 1.0);
  EXPECT_FALSE(s.box_rect(Aabb{dvec3(-0.5, 0, 15), dvec3(0.5, 1, 16)}, lo, hi));  // behind
  // Near the camera a box takes more of the map than the same box far away (the warp).
  dvec2 nlo, nhi, flo, fhi;
  ASSERT_TRUE(s.box_rect(Aabb{dvec3(-0.5, 0, 7), dvec3(0.5, 1, 8)}, nlo, nhi));
  ASSERT_TRUE(s.box_rect(Aabb{dvec3(-0.5, 0, -4), dvec3(0.5, 1, -3)}, flo, fhi));
  EXPECT_GT((nhi.x - nlo.x) * (nhi.y - nlo.y), 2.0 * (fhi.x - flo.x) * (fhi.y - flo.y));
}

TEST(ClusterLayout, HysteresisKeepsAClusteringUntilADistanceMovesTooFar) {
  ClusterSettings settings;
  settings.max_clusters = 4;
  settings.d0 = 0.5;
  settings.hysteresis = 0.5;
  const std::vector<LightView> lights(1);
  const std::vector<Aabb> boxes(3);
  ClusteredLayout layout;
  layout.distances = {points_on_a_line({0.0, 0.1, 1.0}, {true, true, false})};
  const auto now = [](double x, bool third) {
    return std::vector<ObjectDistances>{points_on_a_line({0.0, x, 1.0}, {true, true, third})};
  };
  EXPECT_TRUE(clustering_holds(layout, now(0.3, false), settings));   // moved 0.2 <= 0.25
  EXPECT_FALSE(clustering_holds(layout, now(0.4, false), settings));  // moved 0.3
  EXPECT_FALSE(clustering_holds(layout, now(0.1, true), settings));   // object 2 needs a map
}

DsmSettings clustered(int clusters, int res, float eps, double d0 = 0.5) {
  DsmSettings s;
  s.resolution = res;
  s.eps = eps;
  s.clusters.max_clusters = clusters;
  s.clusters.d0 = d0;
  return s;
}

// Translucent boxes (with media) and spheres in groups of `per_group` around `centres`, on an
// opaque floor of side `floor`, lit by a spot light from above, an omni light to the side and a
// directional light.
Scene grouped_scene(const std::vector<dvec3>& centres, int per_group, double floor, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  test::SceneBuilder b;
  TriangleMesh ground = make_quad(floor);
  b.add(std::move(ground), 1.0);
  for (const dvec3& c : centres)
    for (int k = 0; k < per_group; ++k) {
      const dvec3 p = c + dvec3(u(rng) - 0.5, 0.3 + 0.8 * u(rng), u(rng) - 0.5);
      const double r = 0.15 + 0.15 * u(rng);
      if (k % 2 == 0) {
        b.add(make_box(p - dvec3(r), p + dvec3(r)), 0.3 + 0.4 * u(rng), InteriorKind::constant,
              1.0 + 2.0 * u(rng));
      } else {
        TriangleMesh m = make_icosphere(r, 2);
        for (dvec3& v : m.positions) v += p;
        b.add(std::move(m), 0.2 + 0.5 * u(rng));
      }
    }
  b.spot(dvec3(0.0, 0.75 * floor, 0.0), dvec3(0.0, -1.0, 0.0), 40.0);
  b.omni(dvec3(0.6 * floor, 4.0, 0.0));
  b.directional(glm::normalize(dvec3(0.2, -1.0, 0.3)));
  validate_scene(b.scene);
  return b.scene;
}

Scene sparse_scene() {
  return grouped_scene({{-7.0, 0.0, -7.0}, {7.0, 0.0, -6.0}, {-6.0, 0.0, 7.0}}, 4, 24.0, 1);
}

// Lookups on texel-centre rays of every cluster face match the oracle of a scene holding only
// the cluster's objects: the face sees exactly them, through its cropped projection.
TEST(ClusteredMaps, EachFaceHoldsExactlyItsClusterObjects) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  const float eps = 0.02f;
  DsmSettings s = clustered(4, 48, eps);
  s.bias = 0.0;
  s.slope_bias = 0.0;
  DeepShadowMaps maps(s);
  maps.generate(data, Backend::cpu);
  const ClusteredLayout& c = *maps.clusters();
  ASSERT_EQ(c.resolution, 24);
  const DsmSource source = maps.source();
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> texel(0, 23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0, shadowed = 0;
  for (size_t li = 0; li < c.layout.lights.size(); ++li) {
    const ShadowLight& sl = c.layout.lights[li];
    EXPECT_TRUE(sl.clustered);
    EXPECT_GE(c.clusters[li].size(), 2u) << "light " << li;
    for (int fi = 0; fi < sl.face_count; ++fi) {
      const int face = sl.first_face + fi;
      Scene only = scene;
      only.objects.clear();
      for (int o : c.clusters[li][size_t(c.face_cluster[size_t(face)])])
        only.objects.push_back(scene.objects[size_t(o)]);
      const SceneData only_data(only, Memory::host);
      const ShadowFace& f = c.layout.faces[size_t(face)];
      for (int k = 0; k < 60; ++k) {
        const PixelRay ray = pixel_ray(f.projection, texel(rng), texel(rng));
        const dvec3 p = ray.origin + ray.direction * (u(rng) * 1.2 * data.view().diagonal);
        FacePoint fp;
        if (outside_light_cone(data.host_lights()[li], p) ||
            !project_to_face(f, c.resolution, p, fp))
          continue;
        int hint[4] = {-1, -1, -1, -1};
        const double exact = test::oracle_at(only_data, int(li), p);
        ASSERT_NEAR(source.face_visibility(f, fp, ShadowReceiver{p}, hint), exact, 1.5 * eps + 1e-5)
            << "light " << li << " face " << fi;
        ++checked;
        shadowed += exact < 0.99;
      }
    }
  }
  EXPECT_GT(checked, 400);
  EXPECT_GT(shadowed, checked / 20);
}

struct ErrorFigures {
  double mean = 0.0, max = 0.0;
};

// A point just above the floor (y = 0) looked up as the floor's receiver, with its normal, so
// it gets the surface bias a rendered floor point gets (light_faces.h, receiver_depth).
ShadowReceiver floor_receiver(const dvec3& p) {
  return ShadowReceiver{p, dvec3(0.0, 1.0, 0.0)};
}

// |T - oracle| over points just above the floor around `centre` (half-width `radius`).
ErrorFigures error_near(const SceneData& data, const DsmSource& source, int light,
                        const dvec3& centre, double radius) {
  ErrorFigures e;
  const int n = 40;
  int count = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const dvec3 p = centre + dvec3(radius * (2.0 * (i + 0.5) / n - 1.0), 0.01,
                                     radius * (2.0 * (j + 0.5) / n - 1.0));
      DsmSource::Cursor cursor;
      const double d = std::abs(source.transmittance(cursor, floor_receiver(p), light) -
                                test::oracle_at(data, light, p));
      e.mean += d, e.max = std::max(e.max, d), ++count;
    }
  e.mean /= count;
  return e;
}

// With lispsm the clustering is for a camera 3 units from `near`, looking at it.
ErrorFigures measured_error(const Scene& scene, int clusters, int light, const dvec3& near,
                            bool lispsm = false) {
  const SceneData data(scene, Memory::host);
  DsmSettings s = clustered(clusters, 128, 0.01f);
  s.bilinear = true;
  s.clusters.lispsm = lispsm;
  Camera camera = scene.camera;
  camera.position = near + dvec3(2.0, 2.0, 2.0);
  camera.target = near;
  DeepShadowMaps maps(s);
  maps.generate(data, Backend::cpu, &camera);
  return error_near(data, maps.source(), light, near, 1.5);
}

// Knecht 2011 §5 / Bornik et al. 2012 §5: at equal memory (one 128^2 map against four 64^2
// cluster maps) clustering lowers the error where the camera looks on a sparse scene; on a
// dense one it need not. The numbers go to the test's properties and stdout.
TEST(ClusteredMaps, SparseSceneLowerErrorNearTheCameraAtEqualMemory) {
  const Scene sparse = sparse_scene();
  const dvec3 near_group(-7.0, 0.0, -7.0);
  for (int light : {0, 2}) {  // the spot light above the floor, the directional light
    const ErrorFigures one = measured_error(sparse, 1, light, near_group);
    const ErrorFigures four = measured_error(sparse, 4, light, near_group);
    std::printf(
        "sparse light %d: one 128^2 map mean %.5f max %.4f; 4 clusters of 64^2 mean %.5f "
        "max %.4f\n",
        light, one.mean, one.max, four.mean, four.max);
    RecordProperty("sparse_light" + std::to_string(light) + "_one_map_mean",
                   std::to_string(one.mean));
    RecordProperty("sparse_light" + std::to_string(light) + "_clusters_mean",
                   std::to_string(four.mean));
    EXPECT_LT(four.mean, 0.75 * one.mean) << "light " << light;
    const ErrorFigures warped = measured_error(sparse, 4, light, near_group, true);
    std::printf("sparse light %d: 4 clusters of 64^2 with lispsm mean %.5f max %.4f\n", light,
                warped.mean, warped.max);
    EXPECT_LT(warped.mean, 0.75 * one.mean) << "light " << light;
  }
  // Dense: the same groups close together, filling a floor of their own size.
  const Scene dense =
      grouped_scene({{-1.0, 0.0, -1.0}, {1.0, 0.0, -1.0}, {0.0, 0.0, 1.0}}, 4, 4.0, 1);
  const ErrorFigures one = measured_error(dense, 1, 0, dvec3(-1.0, 0.0, -1.0));
  const ErrorFigures four = measured_error(dense, 4, 0, dvec3(-1.0, 0.0, -1.0));
  std::printf(
      "dense light 0: one 128^2 map mean %.5f max %.4f; 4 clusters of 64^2 mean %.5f max "
      "%.4f\n",
      one.mean, one.max, four.mean, four.max);
  RecordProperty("dense_one_map_mean", std::to_string(one.mean));
  RecordProperty("dense_clusters_mean", std::to_string(four.mean));
}

// Whole clustered lookups (product over the faces that hold a point) against the oracle at
// random points over the groups, at a resolution where the bound dominates.
TEST(ClusteredMaps, LookupsMatchTheOracleForSpotOmniAndDirectional) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  DsmSettings s = clustered(4, 512, 0.01f);
  s.bilinear = true;
  DeepShadowMaps maps(s);
  maps.generate(data, Backend::cpu);
  const DsmSource source = maps.source();
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const dvec3 groups[3] = {{-7.0, 0.0, -7.0}, {7.0, 0.0, -6.0}, {-6.0, 0.0, 7.0}};
  for (int light = 0; light < 3; ++light) {
    double sum = 0.0;
    int count = 0, far_off = 0;
    for (int k = 0; k < 600; ++k) {
      const dvec3 p = groups[k % 3] + dvec3(1.5 * u(rng), 0.9 + 0.9 * u(rng), 1.5 * u(rng));
      DsmSource::Cursor cursor;
      const double d = std::abs(source.transmittance(cursor, ShadowReceiver{p}, light) -
                                test::oracle_at(data, light, p));
      sum += d, ++count, far_off += d > 0.2;
    }
    EXPECT_LT(sum / count, 0.01) << "light " << light;
    EXPECT_LE(far_off, count / 50) << "light " << light;  // silhouettes only
  }
}

// With lispsm the clusters follow the camera: objects it cannot see shadowed get no map, and
// the points it sees still match the oracle.
TEST(ClusteredMaps, LispsmClustersServeTheCamera) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  DsmSettings s = clustered(4, 256, 0.01f);
  s.bilinear = true;
  s.clusters.lispsm = true;
  Camera camera = scene.camera;
  camera.position = dvec3(-4.0, 2.5, -4.0);
  camera.target = dvec3(-7.0, 0.0, -7.0);
  DeepShadowMaps maps(s);
  maps.generate(data, Backend::cpu, &camera);
  int mapped = 0;
  for (const std::vector<int>& c : maps.clusters()->clusters[0]) mapped += int(c.size());
  EXPECT_LT(mapped, int(scene.objects.size()));  // the spot light: some objects culled
  EXPECT_FALSE(maps.clustering_holds(data, &scene.camera));
  EXPECT_TRUE(maps.clustering_holds(data, &camera));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  double sum = 0.0;
  for (int k = 0; k < 300; ++k) {
    const dvec3 p = dvec3(-7.0, 0.01, -7.0) + dvec3(u(rng), 0.0, u(rng));
    DsmSource::Cursor cursor;
    sum += std::abs(maps.source().transmittance(cursor, floor_receiver(p), 0) -
                    test::oracle_at(data, 0, p));
  }
  EXPECT_LT(sum / 300.0, 0.01);
}

TEST(ClusteredMaps, OmniLightToTheSideNeedsFewerThanSixMaps) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  DeepShadowMaps maps(clustered(4, 64, 0.02f));
  maps.generate(data, Backend::cpu);
  const ShadowLight& omni = maps.clusters()->layout.lights[1];
  EXPECT_TRUE(omni.clustered);
  EXPECT_LT(omni.face_count, 4 * 6);
  // Each group lies in one direction from the light; the floor spans several.
  int single = 0;
  for (size_t k = 0; k < maps.clusters()->clusters[1].size(); ++k) {
    int faces = 0;
    for (int i = 0; i < omni.face_count; ++i)
      faces += maps.clusters()->face_cluster[size_t(omni.first_face + i)] == int(k);
    single += faces == 1;
  }
  EXPECT_GE(single, 1);
}

TEST(ClusteredMaps, ShadowMethodParametersStatsAndRebuilds) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  auto method = shadow_registry().create(
      "dsm", StrategyParams::parse({"res=64", "clusters=4", "cluster_d0=0.4"}));
  EXPECT_EQ(method->params()["clusters"], 4);
  EXPECT_EQ(method->params()["cluster_d0"], 0.4);
  EXPECT_EQ(method->params()["lispsm"], 0);
  Camera a = scene.camera, b = scene.camera;
  b.position = dvec3(3.0, 5.0, 9.0);
  method->prepare(data, Backend::cpu, &a);
  method->prepare(data, Backend::cpu, &b);  // the clustering does not depend on the camera
  const nlohmann::json st = method->stats();
  EXPECT_EQ(st["maps_built"], 1);
  EXPECT_EQ(st["cluster_changes"], 0);
  EXPECT_EQ(st["cluster_changed"], nlohmann::json({true, false}));
  EXPECT_EQ(st["resolution"], 32);
  EXPECT_EQ(st["clusters"]["resolution"], 32);
  ASSERT_EQ(st["clusters"]["lights"].size(), 3u);
  for (const nlohmann::json& l : st["clusters"]["lights"]) {
    EXPECT_LE(l["clusters"].size(), 4u);
    for (const nlohmann::json& c : l["clusters"]) {
      EXPECT_GE(c["objects"].size(), 1u);
      EXPECT_GE(c["faces"].size(), 1u);
    }
  }
  EXPECT_THROW(shadow_registry().create("dsm", StrategyParams::parse({"clusters=0"})), InputError);
  EXPECT_THROW(shadow_registry().create("dsm", StrategyParams::parse({"cluster_d0=-1"})),
               InputError);
  EXPECT_THROW(shadow_registry().create("dsm", StrategyParams::parse({"lispsm=2"})), InputError);
}

// Eq. 3.9 needs every light's own maps: 20 spot, omni and directional lights (beyond
// kDsmCursorLights, which only limits coherent search) each match the oracle, unclustered and
// clustered, through the shadow method's probe.
TEST(ManyLights, TwentyLightsEachMatchTheOracle) {
  Scene scene = test::random_scene(21);
  scene.lights.clear();
  test::SceneBuilder lights;
  for (int k = 0; k < 20; ++k) {
    const double a = 6.283185307179586 * k / 20.0;
    const dvec3 p(4.0 * std::cos(a), 4.5 + 0.5 * (k % 3), 4.0 * std::sin(a));
    if (k % 3 == 0) lights.spot(p, glm::normalize(-p), 35.0);
    if (k % 3 == 1) lights.omni(p);
    if (k % 3 == 2) lights.directional(glm::normalize(dvec3(-p.x, -6.0, -p.z)));
  }
  scene.lights = lights.scene.lights;
  const SceneData data(scene, Memory::host);
  std::mt19937 rng(8);
  std::vector<dvec3> points;
  for (int i = 0; i < 200; ++i)
    points.push_back(dvec3(std::uniform_real_distribution<double>(-2.0, 2.0)(rng),
                           std::uniform_real_distribution<double>(0.0, 2.0)(rng),
                           std::uniform_real_distribution<double>(-2.0, 2.0)(rng)));
  auto reference = shadow_registry().create("reference");
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  for (const char* clusters : {"clusters=1", "clusters=4"}) {
    auto method = shadow_registry().create(
        "dsm", StrategyParams::parse({"res=256", "eps=0.01", "filter=bilinear", clusters}));
    const ProbeResults r = probe_transmittance(Backend::cpu, data, *method, points);
    ASSERT_EQ(r.transmittance.size(), exact.transmittance.size());
    for (int l = 0; l < 20; ++l) {
      double sum = 0.0;
      for (size_t i = 0; i < points.size(); ++i) {
        const size_t k = i * 20 + size_t(l);
        sum += std::abs(r.transmittance[k] - exact.transmittance[k]);
      }
      EXPECT_LT(sum / double(points.size()), 0.04) << clusters << " light " << l;
    }
  }
}

// The many-lights benchmark scene loads with its 32 lights and renders with clustered maps for
// every light (each light's maps, at most 4 clusters, omni lights in cropped cube faces).
TEST(ManyLights, ThirtyTwoLightSceneRenders) {
  Scene scene = test::scene_file("knecht-32-lights.json");
  int spots = 0, omnis = 0;
  for (const Light& l : scene.lights) {
    spots += l.type == LightType::spot;
    omnis += l.type == LightType::omni;
  }
  EXPECT_EQ(spots, 16);
  EXPECT_EQ(omnis, 16);
  scene.camera.width = 48;
  scene.camera.height = 32;
  const SceneData data(scene, Memory::host);
  auto method = shadow_registry().create(
      "dsm", StrategyParams::parse({"res=32", "clusters=4", "filter=bilinear"}));
  const RasterRenderResult r =
      render_raster(Backend::cpu, data, scene.camera, *method, scene.background);
  EXPECT_EQ(r.render.counters.overflow_pixels, 0u);
  const nlohmann::json st = method->stats();
  ASSERT_EQ(st["clusters"]["lights"].size(), 32u);
  for (const nlohmann::json& l : st["clusters"]["lights"]) {
    EXPECT_GE(l["maps"].get<int>(), 1);
    EXPECT_LE(l["clusters"].size(), 4u);
  }
  double sum = 0.0;
  for (float v : r.render.image.rgb) sum += v;
  EXPECT_GT(sum, 0.0);
}

// With lispsm the maps follow the camera: a small move keeps them (hysteresis), a move to
// another group rebuilds them.
TEST(ClusteredMaps, LispsmRebuildsWhenTheClusteringNoLongerHolds) {
  const Scene scene = sparse_scene();
  const SceneData data(scene, Memory::host);
  auto method =
      shadow_registry().create("dsm", StrategyParams::parse({"res=64", "clusters=4", "lispsm=1"}));
  Camera a = scene.camera;
  a.position = dvec3(-4.0, 2.5, -4.0);
  a.target = dvec3(-7.0, 0.0, -7.0);
  Camera nudged = a;
  nudged.position += dvec3(0.01, 0.0, 0.0);
  Camera other = a;
  other.position = dvec3(4.0, 2.5, -3.0);
  other.target = dvec3(7.0, 0.0, -6.0);
  for (const Camera* c : {&a, &nudged, &other}) method->prepare(data, Backend::cpu, c);
  const nlohmann::json st = method->stats();
  EXPECT_EQ(st["cluster_changed"], nlohmann::json({true, false, true}));
  EXPECT_EQ(st["maps_built"], 2);
  EXPECT_EQ(st["cluster_changes"], 1);
}

// CPU and CUDA: the same clusters, node counts per texel and lookups (skipped without a GPU).
TEST(ClusteredMaps, CpuAndCudaAgree) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const Scene& scene : {sparse_scene(), test::scene_file("many-objects.json")}) {
    const SceneData host(scene, Memory::host), device(scene, Memory::device);
    DeepShadowMaps cpu(clustered(4, 64, 0.02f)), gpu(clustered(4, 64, 0.02f));
    cpu.generate(host, Backend::cpu);
    gpu.generate(device, Backend::cuda);
    EXPECT_EQ(cpu.clusters()->signature, gpu.clusters()->signature);
    const std::vector<DsmTexelRecord>& a = cpu.records();
    const std::vector<DsmTexelRecord>& b = gpu.records();
    ASSERT_EQ(a.size(), b.size());
    int64_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += a[i].nodes != b[i].nodes;
    EXPECT_LE(double(differ), 1e-4 * double(a.size())) << differ << " texels";
    auto mc = shadow_registry().create("dsm", StrategyParams::parse({"res=64", "clusters=4"}));
    auto mg = shadow_registry().create("dsm", StrategyParams::parse({"res=64", "clusters=4"}));
    std::mt19937 rng(3);
    std::vector<dvec3> points;
    const Aabb box = world_bounds(scene);
    for (int i = 0; i < 2000; ++i) {
      dvec3 p;
      for (int k = 0; k < 3; ++k)
        p[k] = std::uniform_real_distribution<double>(box.lo[k], box.hi[k])(rng);
      points.push_back(p);
    }
    const ProbeResults c = probe_transmittance(Backend::cpu, host, *mc, points);
    const ProbeResults g = probe_transmittance(Backend::cuda, device, *mg, points);
    ASSERT_EQ(c.transmittance.size(), g.transmittance.size());
    int64_t lookups_differ = 0;
    for (size_t i = 0; i < c.transmittance.size(); ++i)
      lookups_differ += std::abs(c.transmittance[i] - g.transmittance[i]) > 1e-6;
    EXPECT_LE(double(lookups_differ), 1e-3 * double(c.transmittance.size()));
  }
}

}  // namespace
}  // namespace dv
