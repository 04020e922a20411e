// The camera pass's lanes per pixel (frame/fragment_lanes.h, frame/shade_payload.h): a pixel's
// volume steps split into shares and folded give the colour of one lane marching them all, and
// the pass's layout gives every pixel of the view exactly one group of lanes, and CUDA lanes
// that exchange their shares by warp shuffles give the CPU's image (skipped without a GPU).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "cuda/device_memory.h"
#include "frame/fragment_lanes.h"
#include "frame/raster_render.h"
#include "frame/shade_payload.h"
#include "load/scene_loader.h"
#include "renderer/camera_rays.h"
#include "strategies/shadow/shadow_device.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/support/paths.h"

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
  Scene scene = load_scene(test::source_dir() + "/scenes/knecht-fig56.json");
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

TEST(VolumeLanes, EveryPixelGetsOneGroupOfLanes) {
  const Scene scene = load_scene(test::source_dir() + "/scenes/knecht-fig56.json");
  const SceneData data(scene, Memory::host);
  const SceneView& view = data.view();
  const RasterProjection projection = make_camera_projection(scene.camera, view.bounds);
  const TileLists lists = rasterize_tiles(Backend::cpu, view, projection);
  const InsideSet eye = media_containing(view, scene.camera.position).inside;
  const FragmentOrder order = order_fragment_tiles(Backend::cpu, view, lists.view(), &eye);
  const int64_t volume_tiles = order.volume_tiles();
  EXPECT_GT(volume_tiles, 0);
  EXPECT_LT(volume_tiles, lists.tile_count());
  const std::vector<int32_t> tiles = order.order.to_vector();
  EXPECT_EQ(std::set<int32_t>(tiles.begin(), tiles.end()).size(), size_t(lists.tile_count()));
  std::map<std::pair<int, int>, std::pair<int, int>> seen;  // pixel: (lanes, ranks seen bits)
  int64_t shared_pixels = 0;
  for (int64_t i = 0; i < fragment_thread_count(lists.tile_count()); ++i) {
    int x, y;
    LaneGroup g;
    if (!pixel_of_fragment_thread(i, order.view(), projection.width, projection.height, x, y, g))
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
  ASSERT_EQ(seen.size(), size_t(projection.width) * projection.height);
  for (const auto& [pixel, group] : seen) ASSERT_EQ(group.second, (1 << group.first) - 1);
  // 720 x 480: whole tiles only.
  EXPECT_EQ(shared_pixels, volume_tiles * kTileSide * kTileSide);
}

TEST(VolumeLanes, CudaSharesGiveTheCpuImage) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  for (const char* shadows : {"none", "shadowmap"}) {
    const Scene scene = load_scene(test::source_dir() + "/scenes/knecht-fig56.json");
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

}  // namespace
}  // namespace dv
