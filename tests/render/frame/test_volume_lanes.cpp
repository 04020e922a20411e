// The camera pass's lanes per pixel and tile order (render/frame/fragment_lanes.h,
// render/frame/shade_payload.h): a pixel's volume steps split into shares and folded give the
// colour of one lane marching them all; the pass's layout gives every pixel of the view exactly one
// group of lanes; the volume tiles come first, by decreasing cost estimate from the occupied bricks
// along probe rays; CUDA lanes that exchange their shares by warp shuffles give the CPU's image and
// the CUDA order is the CPU's (skipped without a GPU).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <span>
#include <string>
#include <utility>

#include "cuda/device_memory.h"
#include "engine/raster/camera_rays.h"
#include "experiments/source_paths.h"
#include "render/frame/fragment_lanes.h"
#include "render/frame/raster_render.h"
#include "render/frame/shade_payload.h"
#include "render/load/mesh_generators.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_device.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

struct PixelResult {
  dvec3 color, transmittance;
  unsigned long long samples;
};

PixelResult walk_with_lanes(const SceneView& s, const dvec3& origin, const dvec3& dir, int lanes) {
  const NoShadowSource none;
  ShadePayload<NoShadowSource> payload{s, none, origin, dir};
  payload.lanes = LaneGroup{0, lanes};
  const BvhFragments fragments{&s, make_sheared_ray(origin, dir)};
  walk_fragments(s, fragments, media_containing(s, origin).inside, 0.0, 0.0, 1e300, payload);
  return {payload.color, payload.transmittance, payload.samples};
}

TEST(VolumeLanes, SharedStepsComposeAsOneLane) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  scene.camera.width = 72;
  scene.camera.height = 48;
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const CameraView cam = make_camera_view(scene.camera);
  int with_samples = 0;
  for (int y = 0; y < scene.camera.height; y += 3)
    for (int x = 0; x < scene.camera.width; x += 3) {
      const dvec3 dir = camera_ray_direction(cam, x, y);
      const PixelResult one = walk_with_lanes(s, scene.camera.position, dir, 1);
      with_samples += one.samples > 16;
      for (int lanes : {2, 4, 8}) {
        const PixelResult split = walk_with_lanes(s, scene.camera.position, dir, lanes);
        for (int c = 0; c < 3; ++c) {
          // Apart from rounding, a share marches on past where the whole ray saturated, and
          // what it adds there is below kSaturatedTransmittance of the colour.
          EXPECT_NEAR(split.color[c], one.color[c], 1e-6) << x << "," << y << " lanes " << lanes;
          EXPECT_NEAR(split.transmittance[c], one.transmittance[c], 1e-6) << x << "," << y;
        }
        EXPECT_GE(split.samples, one.samples) << x << "," << y << " lanes " << lanes;
      }
    }
  EXPECT_GT(with_samples, 20);
}

// knecht-fig56 on the CPU: its tile lists and the camera pass's tile order.
struct Fig56Tiles {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  SceneData data{scene, Memory::host};
  RasterProjection projection = make_camera_projection(scene.camera, data.view().bounds);
  TileLists lists = rasterize_tiles(Backend::cpu, data.view(), projection);
  InsideSet eye = media_containing(data.view(), scene.camera.position).inside;
  FragmentOrder order =
      order_fragment_tiles(Backend::cpu, data.view(), projection, lists.view(), &eye);
};

TEST(VolumeLanes, EveryPixelGetsOneGroupOfLanes) {
  const Fig56Tiles f;
  const int64_t volume_tiles = f.order.volume_tiles();
  EXPECT_GT(volume_tiles, 0);
  EXPECT_LT(volume_tiles, f.lists.tile_count());
  const std::vector<int32_t> tiles = f.order.order.to_vector();
  EXPECT_EQ(std::set<int32_t>(tiles.begin(), tiles.end()).size(), size_t(f.lists.tile_count()));
  std::map<std::pair<int, int>, std::pair<int, int>> seen;  // pixel: (lanes, ranks seen bits)
  int64_t shared_pixels = 0;
  for (int64_t i = 0; i < fragment_thread_count(f.lists.tile_count()); ++i) {
    int x, y;
    LaneGroup g;
    if (!pixel_of_fragment_thread(i, f.order.view(), f.projection.width, f.projection.height, x, y,
                                  g))
      continue;
    auto& [lanes, ranks] = seen[{x, y}];
    if (ranks == 0) lanes = g.count;
    ASSERT_EQ(lanes, g.count) << x << "," << y;
    ASSERT_EQ(ranks & (1 << g.rank), 0) << x << "," << y << " rank " << g.rank;
    ranks |= 1 << g.rank;
    // A group is g.count consecutive threads starting at a multiple of g.count.
    ASSERT_EQ(i % g.count, g.rank);
    shared_pixels += g.count > 1 && g.rank == 0;
  }
  ASSERT_EQ(seen.size(), size_t(f.projection.width) * f.projection.height);
  for (const auto& [pixel, group] : seen) ASSERT_EQ(group.second, (1 << group.first) - 1);
  // 720 x 480: whole tiles only.
  EXPECT_EQ(shared_pixels, volume_tiles * kTileSide * kTileSide);
}

// A 33^3 grid over [0, 8]^3 (4 bricks of 2 world units per axis) whose density is 0 except
// at the samples x = 17 .. 23: only the bricks at x in [4, 6] are occupied.
TEST(VolumeLanes, OccupiedBrickLengthCountsOnlyOccupiedBricks) {
  test::SceneBuilder b;
  VolumeGrid g;
  g.name = "slab";
  g.dims = {33, 33, 33};
  g.spacing = {0.25, 0.25, 0.25};
  g.origin = {0.0, 0.0, 0.0};
  for (int z = 0; z < 33; ++z)
    for (int y = 0; y < 33; ++y)
      for (int x = 0; x < 33; ++x) g.density.push_back(x >= 17 && x <= 23 ? 1.0f : 0.0f);
  b.scene.volumes.push_back(g);
  Object& v = b.add(make_box(g.bounds().lo, g.bounds().hi), 0.0, InteriorKind::volume);
  v.interior.volume = 0;
  v.interior.transfer.points = {{0.0, dvec3(1.0), 0.0}, {1.0, dvec3(1.0), 3.0}};
  const SceneData data = b.build();
  const SceneView& s = data.view();
  const ObjectView& o = s.objects[0];
  ASSERT_EQ(o.interior, InteriorKind::volume);
  const auto length = [&](dvec3 origin, dvec3 dir, double t_min = 0.0) {
    return occupied_brick_length(s, o, origin, dir, t_min);
  };
  EXPECT_NEAR(length({-1, 4.1, 4.1}, {1, 0, 0}), 2.0, 1e-9);       // through the slab
  EXPECT_NEAR(length({9, 4.1, 4.1}, {-1, 0, 0}), 2.0, 1e-9);       // backwards, faces on bricks
  EXPECT_NEAR(length({5, 4.1, 4.1}, {1, 0, 0}), 1.0, 1e-9);        // from inside the slab
  EXPECT_NEAR(length({-1, 4.1, 4.1}, {1, 0, 0}, 6.5), 0.5, 1e-9);  // from t_min in it
  EXPECT_NEAR(length({-1, 4.1, 4.1}, {1, 0, 0}, 7.5), 0.0, 1e-9);  // starting past it
  EXPECT_NEAR(length({1, -1, 4.1}, {0, 1, 0}), 0.0, 1e-9);         // through empty bricks only
  EXPECT_NEAR(length({5, -1, 4.1}, {0, 1, 0}), 8.0, 1e-9);         // along the slab
  EXPECT_NEAR(length({5, 9, 4.1}, {1, 0, 0}), 0.0, 1e-9);          // outside the grid
  const dvec3 diagonal = glm::normalize(dvec3(1, 1, 0));
  EXPECT_NEAR(length({0, 0, 4.1}, diagonal), 2.0 * std::sqrt(2.0), 1e-9);
}

// The volume tiles first, by non-increasing volume_tile_cost, ties in tile order; then the
// other tiles in tile order.
TEST(VolumeLanes, VolumeTilesComeHeaviestFirst) {
  const Fig56Tiles f;
  const SceneView& view = f.data.view();
  const std::vector<int32_t> tiles = f.order.order.to_vector();
  const int64_t volume_tiles = f.order.volume_tiles();
  const TileListsView lists = f.lists.view();
  const auto crosses_a_volume = [&](int32_t t) {
    for (uint32_t k = lists.offsets[t]; k < lists.offsets[t + 1]; ++k)
      if (view.objects[view.triangle_object[lists.entries[k].triangle]].interior ==
          InteriorKind::volume)
        return true;
    return false;
  };
  uint32_t previous_cost = kMostTileCost + 1;
  int32_t previous_tile = -1;
  std::set<uint32_t> costs;
  for (int64_t r = 0; r < int64_t(tiles.size()); ++r) {
    const int32_t t = tiles[size_t(r)];
    const bool volume = r < volume_tiles;
    ASSERT_EQ(crosses_a_volume(t), volume) << "tile " << t << " at " << r;
    const uint32_t cost = volume ? volume_tile_cost(view, f.projection, t) : 0;
    if (r == volume_tiles) previous_cost = 0, previous_tile = -1;
    ASSERT_LE(cost, previous_cost) << "tile " << t << " at " << r;
    if (cost == previous_cost) {
      ASSERT_GT(t, previous_tile) << "tile " << t << " at " << r;
    }
    if (volume) {
      ASSERT_GE(cost, 1u);
      costs.insert(cost);
    }
    previous_cost = cost, previous_tile = t;
  }
  // The estimate tells the tiles apart: fig56's volume tiles span many costs.
  EXPECT_GT(costs.size(), 50u);
  EXPECT_GT(*costs.rbegin(), 100u);
}

TEST(VolumeLanes, CudaSharesGiveTheCpuImage) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  for (const char* shadows : {"none", "shadowmap"}) {
    const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
    const SceneData host(scene, Memory::host), device(scene, Memory::device);
    auto method = shadow_registry().create(shadows);
    const RasterRenderResult c =
        render_raster(Backend::cpu, host, scene.camera, *method, scene.background);
    const RasterRenderResult g =
        render_raster(Backend::cuda, device, scene.camera, *method, scene.background);
    EXPECT_GT(c.volume_tiles, 0) << shadows;
    EXPECT_EQ(c.volume_tiles, g.volume_tiles) << shadows;
    EXPECT_EQ(c.render.counters.hits, g.render.counters.hits) << shadows;
    EXPECT_EQ(c.render.counters.volume_samples, g.render.counters.volume_samples) << shadows;
    double worst = 0.0;
    for (size_t i = 0; i < c.render.image.rgb.size(); ++i)
      worst = std::max(worst, double(std::abs(c.render.image.rgb[i] - g.render.image.rgb[i])));
    EXPECT_LE(worst, 1e-6) << shadows;
  }
}

TEST(VolumeLanes, CudaOrdersTheTilesAsTheCpu) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  const SceneData host(scene, Memory::host), device(scene, Memory::device);
  const RasterProjection projection = make_camera_projection(scene.camera, host.view().bounds);
  const InsideSet eye = media_containing(host.view(), scene.camera.position).inside;
  Buffer<InsideSet> device_eye(Memory::device, std::span<const InsideSet>(&eye, 1));
  const TileLists cpu_lists = rasterize_tiles(Backend::cpu, host.view(), projection);
  const TileLists cuda_lists = rasterize_tiles(Backend::cuda, device.view(), projection);
  const FragmentOrder c =
      order_fragment_tiles(Backend::cpu, host.view(), projection, cpu_lists.view(), &eye);
  const FragmentOrder g = order_fragment_tiles(Backend::cuda, device.view(), projection,
                                               cuda_lists.view(), device_eye.data());
  EXPECT_GT(c.volume_tiles(), 0);
  EXPECT_EQ(c.volume_tiles(), g.volume_tiles());
  EXPECT_EQ(c.order.to_vector(), g.order.to_vector());
}

}  // namespace
}  // namespace dv
