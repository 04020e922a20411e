// Tile lists of the rasterizer: offsets, ordering and counts against a brute-force serial
// binning of the same setup, the overflow report when the entry limit is too small, sets of
// projections binned together against runs of their own, identical lists on CPU and CUDA, and
// the projection helpers (pixel rays, light views, input checks).
#include <map>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

#include "render/load/mesh_generators.h"
#include "tests/engine/raster/raster_test_support.h"

namespace dv {
namespace {

class TileListsTest : public test::RasterBackendTest {};

// A bit of everything: a closed sphere, a tilted grid, a triangle cut by the near plane, a huge
// one, a degenerate one and one behind the camera.
struct MixedScene {
  Camera camera = test::test_camera({0.2, 0.1, 3.0}, {0.0, 0.0, 0.0}, 203, 149, 0.3);
  test::Soup soup;
  MixedScene() {
    soup.add(make_icosphere(0.7, 3), glm::translate(dmat4(1.0), dvec3(-0.3, 0.1, 0.2)));
    dmat4 tilt = glm::rotate(dmat4(1.0), glm::radians(75.0), dvec3(1.0, 0.2, 0.0));
    soup.add(make_subdivided_quad(2.2, 800), tilt);
    soup.add_triangle({-0.5, -0.6, 1.0}, {0.7, -0.4, 1.2}, {0.1, 0.3, 4.0});
    soup.add_triangle({-1e6, -1e6, -2.0}, {1e6, -1e6, -2.0}, {0.0, 1e6, -2.0});
    soup.add_triangle({0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}, {1.0, 1.0, 1.0});  // repeated corner
    soup.add_triangle({0.0, 0.0, 5.0}, {1.0, 0.0, 5.0}, {0.0, 1.0, 5.0});
  }
  RasterProjection projection() const { return make_camera_projection(camera, 20.0); }
};

bool entry_less(const TileEntry& a, const TileEntry& b) {
  return a.triangle != b.triangle ? a.triangle < b.triangle : a.mask < b.mask;
}

// Serial binning straight from setup_triangle and tile_coverage over every tile of the image.
std::vector<std::vector<TileEntry>> brute_force_lists(const test::Soup& soup,
                                                      const RasterProjection& p) {
  const int tiles_x = (p.width + 7) / 8, tiles_y = (p.height + 7) / 8;
  std::vector<std::vector<TileEntry>> lists(size_t(tiles_x) * tiles_y);
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const u32vec3 t = soup.triangles[i];
    const dvec3 world[3] = {soup.vertices[t.x], soup.vertices[t.y], soup.vertices[t.z]};
    setup_triangle(p, world, uint32_t(i), [&](const RasterTriangle& piece) {
      for (int ty = 0; ty < tiles_y; ++ty)
        for (int tx = 0; tx < tiles_x; ++tx) {
          const uint64_t mask =
              tile_coverage(piece, tx, ty, tile_valid_mask(tx, ty, p.width, p.height));
          if (mask) lists[size_t(ty) * tiles_x + tx].push_back({mask, uint32_t(i), 0u});
        }
    });
  }
  for (auto& list : lists) std::sort(list.begin(), list.end(), entry_less);
  return lists;
}

void expect_same_entries(const std::vector<TileEntry>& got, const std::vector<TileEntry>& want,
                         int64_t tile) {
  ASSERT_EQ(got.size(), want.size()) << "tile " << tile;
  for (size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].triangle, want[k].triangle) << "tile " << tile << " entry " << k;
    EXPECT_EQ(got[k].mask, want[k].mask) << "tile " << tile << " entry " << k;
    EXPECT_EQ(got[k].reserved, 0u);
  }
}

TEST_P(TileListsTest, ListsMatchBruteForceBinning) {
  const MixedScene scene;
  const RasterProjection p = scene.projection();
  const test::RasterRun run = test::rasterize(backend(), scene.soup, p);
  const TileLists& lists = run.lists;
  ASSERT_EQ(lists.tiles_x, 26);
  ASSERT_EQ(lists.tiles_y, 19);
  const std::vector<uint32_t> offsets = lists.offsets.to_vector();
  ASSERT_EQ(int64_t(offsets.size()), lists.tile_count() + 1);
  EXPECT_EQ(offsets.front(), 0u);
  EXPECT_EQ(int64_t(offsets.back()), lists.entries.size());
  EXPECT_TRUE(std::is_sorted(offsets.begin(), offsets.end()));
  const auto want = brute_force_lists(scene.soup, p);
  int64_t total = 0, most = 0;
  for (int64_t t = 0; t < lists.tile_count(); ++t) {
    const std::vector<TileEntry> got = test::tile_entries(lists, t);
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end(), entry_less)) << "tile " << t;
    expect_same_entries(got, want[size_t(t)], t);
    total += int64_t(want[size_t(t)].size());
    most = std::max<int64_t>(most, int64_t(want[size_t(t)].size()));
  }
  const RasterStats& s = lists.stats;
  EXPECT_EQ(s.entries, total);
  EXPECT_EQ(s.entries_needed, total);
  EXPECT_EQ(s.max_entries_per_tile, most);
  EXPECT_GT(s.max_entries_per_tile, 16);  // long lists take the heap-sort path
  EXPECT_FALSE(s.overflow);
  EXPECT_EQ(s.first_incomplete_tile, lists.tile_count());
  EXPECT_EQ(s.triangles_in, int64_t(scene.soup.triangles.size()));
  EXPECT_EQ(s.culled_degenerate, 1);
  EXPECT_EQ(s.culled_behind, 1);
  EXPECT_GE(s.clipped_near, 1);
  EXPECT_GE(s.clipped_guard, 1);
  EXPECT_EQ(s.triangles_culled,
            s.culled_behind + s.culled_offscreen + s.culled_degenerate + s.culled_invalid);
  EXPECT_GT(s.pieces, s.triangles_rasterized);  // clipping made extra pieces
  // Per-pixel counts of the backend equal those read from the lists on the host.
  const TileListsView v = lists.view();
  for (int y = 0; y < run.height; ++y)
    for (int x = 0; x < run.width; ++x)
      ASSERT_EQ(run.count(x, y), uint32_t(fragment_count(v, x, y)));
}

// The mixed scene with a stack of 100 triangles over the same tiles: lists up to 64 entries
// are sorted by rank, one thread per entry, longer ones one thread per list; both give the
// brute-force order.
TEST_P(TileListsTest, LongAndShortListsMatchBruteForceBinning) {
  MixedScene scene;
  for (int k = 0; k < 100; ++k) {
    const double z = 0.5 + 0.001 * k;
    scene.soup.add_triangle({-0.3, -0.3, z}, {0.3, -0.25, z}, {0.0, 0.3, z});
  }
  const RasterProjection p = scene.projection();
  const TileLists& lists = test::rasterize(backend(), scene.soup, p).lists;
  const auto want = brute_force_lists(scene.soup, p);
  int64_t short_lists = 0, long_lists = 0;
  for (int64_t t = 0; t < lists.tile_count(); ++t) {
    const size_t n = want[size_t(t)].size();
    short_lists += n > 1 && n <= 64;
    long_lists += n > 64;
    expect_same_entries(test::tile_entries(lists, t), want[size_t(t)], t);
  }
  EXPECT_GT(short_lists, 10);
  EXPECT_GT(long_lists, 10);
}

TEST_P(TileListsTest, OverflowIsReportedAndNothingIsWrittenBeyondTheLimit) {
  const MixedScene scene;
  const test::RasterRun full = test::rasterize(backend(), scene.soup, scene.projection());
  const int64_t needed = full.lists.stats.entries;
  ASSERT_GT(needed, 100);
  for (const int64_t limit : {needed / 2, int64_t(0), needed - 1}) {
    RasterOptions options;
    options.max_entries = limit;
    const test::RasterRun cut = test::rasterize(backend(), scene.soup, scene.projection(), options);
    const RasterStats& s = cut.lists.stats;
    EXPECT_TRUE(s.overflow) << "limit " << limit;
    EXPECT_EQ(s.entries_needed, needed);
    EXPECT_LE(s.entries, limit);
    EXPECT_EQ(cut.lists.entries.size(), s.entries);
    EXPECT_GT(s.dropped_tiles, 0);
    const std::vector<uint32_t> offsets = cut.lists.offsets.to_vector();
    EXPECT_TRUE(std::is_sorted(offsets.begin(), offsets.end()));
    EXPECT_EQ(int64_t(offsets.back()), s.entries);
    int64_t dropped = 0;
    for (int64_t t = 0; t < cut.lists.tile_count(); ++t) {
      const std::vector<TileEntry> got = test::tile_entries(cut.lists, t);
      const std::vector<TileEntry> complete = test::tile_entries(full.lists, t);
      if (t < s.first_incomplete_tile) {
        expect_same_entries(got, complete, t);
      } else {
        EXPECT_TRUE(got.empty()) << "tile " << t;
        dropped += !complete.empty();
      }
    }
    EXPECT_EQ(dropped, s.dropped_tiles);
  }
  RasterOptions exact;
  exact.max_entries = needed;
  EXPECT_FALSE(
      test::rasterize(backend(), scene.soup, scene.projection(), exact).lists.stats.overflow);
}

// MixedScene seen from four cameras of one image size (one looks away and sees nothing), the
// soup in the backend's memory.
struct MixedSet {
  MixedScene scene;
  std::vector<RasterProjection> projections;
  Buffer<dvec3> vertices;
  Buffer<u32vec3> triangles;
  explicit MixedSet(Backend backend) {
    const dvec3 eyes[] = {{0.2, 0.1, 3.0}, {2.5, 1.0, 0.5}, {-0.4, 2.8, 0.9}, {0.0, 0.0, 30.0}};
    const dvec3 targets[] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 60.0}};
    for (int k = 0; k < 4; ++k)
      projections.push_back(make_camera_projection(
          test::test_camera(eyes[k], targets[k], scene.camera.width, scene.camera.height, 0.3),
          20.0));
    const Memory memory = memory_of(backend);
    vertices = Buffer<dvec3>(memory, std::span<const dvec3>(scene.soup.vertices), "test vertices");
    triangles =
        Buffer<u32vec3>(memory, std::span<const u32vec3>(scene.soup.triangles), "test triangles");
  }
  TileListSet rasterize(Backend backend, const RasterOptions& options = {}) const {
    return rasterize_tile_set(backend, vertices.const_view(), triangles.const_view(), projections,
                              options);
  }
};

// Projection p's entries of tile t of a set, copied to the host.
std::vector<TileEntry> set_tile_entries(const TileListSet& set, int p, int64_t t) {
  const std::vector<uint32_t> offsets = set.offsets.to_vector();
  const std::vector<TileEntry> entries = set.entries.to_vector();
  const int64_t k = p * set.tile_count() + t;
  return std::vector<TileEntry>(entries.begin() + offsets[size_t(k)],
                                entries.begin() + offsets[size_t(k) + 1]);
}

// One run over every (projection, triangle) pair gives each projection the lists, counts and
// stats of a run of its own.
TEST_P(TileListsTest, SetOfProjectionsGivesEachItsOwnLists) {
  const MixedSet set(backend());
  const TileListSet lists = set.rasterize(backend());
  ASSERT_EQ(lists.projections(), 4);
  int64_t total = 0;
  for (int p = 0; p < 4; ++p) {
    const test::RasterRun alone = test::rasterize(backend(), set.scene.soup, set.projections[p]);
    ASSERT_EQ(lists.tile_count(), alone.lists.tile_count());
    for (int64_t t = 0; t < lists.tile_count(); ++t)
      expect_same_entries(set_tile_entries(lists, p, t), test::tile_entries(alone.lists, t), t);
    const nlohmann::json got = lists.stats[size_t(p)], want = alone.lists.stats;
    EXPECT_EQ(got, want) << "projection " << p;
    // view(p) over host copies: the same fragments per pixel as the run of its own.
    const TileListsView v = lists.view(p);
    ASSERT_EQ(v.offsets.size, lists.tile_count() + 1);
    const std::vector<uint32_t> offsets = lists.offsets.to_vector();
    const std::vector<TileEntry> entries = lists.entries.to_vector();
    const TileListsView host{v.width,
                             v.height,
                             v.tiles_x,
                             v.tiles_y,
                             {offsets.data() + p * lists.tile_count(), v.offsets.size},
                             {entries.data(), int64_t(entries.size())}};
    int64_t differing = 0;
    for (int y = 0; y < alone.height; ++y)
      for (int x = 0; x < alone.width; ++x)
        differing += uint32_t(fragment_count(host, x, y)) != alone.count(x, y);
    EXPECT_EQ(differing, 0) << "projection " << p;
    total += lists.stats[size_t(p)].entries;
  }
  EXPECT_GT(lists.stats[0].entries, 100);
  EXPECT_EQ(lists.stats[3].entries, 0);  // the camera that looks away
  EXPECT_EQ(total, lists.entries.size());
}

// A set shares the entry limit: the lists are complete up to the first tile, in projection
// order, that does not fit, and empty from there on, which each projection's stats report.
TEST_P(TileListsTest, SetOverflowCutsAtTheFirstTileThatDoesNotFit) {
  const MixedSet set(backend());
  const TileListSet full = set.rasterize(backend());
  RasterOptions options;
  options.max_entries = full.stats[0].entries + full.stats[1].entries / 2;
  const TileListSet cut = set.rasterize(backend(), options);
  EXPECT_FALSE(cut.stats[0].overflow);
  EXPECT_EQ(cut.stats[0].first_incomplete_tile, cut.tile_count());
  EXPECT_TRUE(cut.stats[1].overflow);
  EXPECT_TRUE(cut.stats[2].overflow);
  EXPECT_FALSE(cut.stats[3].overflow);  // nothing to drop
  int64_t stored = 0;
  for (int p = 0; p < 4; ++p) {
    const RasterStats& s = cut.stats[size_t(p)];
    EXPECT_EQ(s.entries_needed, full.stats[size_t(p)].entries) << "projection " << p;
    int64_t dropped = 0;
    for (int64_t t = 0; t < cut.tile_count(); ++t) {
      const std::vector<TileEntry> got = set_tile_entries(cut, p, t);
      const std::vector<TileEntry> complete = set_tile_entries(full, p, t);
      if (t < s.first_incomplete_tile) {
        expect_same_entries(got, complete, t);
      } else {
        EXPECT_TRUE(got.empty()) << "projection " << p << " tile " << t;
        dropped += !complete.empty();
      }
    }
    EXPECT_EQ(dropped, s.dropped_tiles) << "projection " << p;
    stored += s.entries;
  }
  EXPECT_EQ(stored, cut.entries.size());
  EXPECT_LE(stored, options.max_entries);
}

TEST_P(TileListsTest, SetOfProjectionsOfTwoSizesIsAnInputError) {
  MixedSet set(backend());
  set.projections[2].width += 8;
  EXPECT_THROW(set.rasterize(backend()), InputError);
}

TEST_P(TileListsTest, OutOfRangeIndicesAreCulledNotRead) {
  test::Soup soup;
  soup.add_triangle({1.5, 1.5, 0}, {9.5, 1.5, 0}, {1.5, 9.5, 0});
  soup.triangles.push_back({0, 1, 7});
  soup.add_triangle({1.0, 1.0, 0}, {std::nan(""), 2.0, 0}, {3.0, 9.0, 0});
  const test::RasterRun run = test::rasterize(backend(), soup, make_screen_projection(12, 12));
  EXPECT_EQ(run.lists.stats.culled_invalid, 2);
  EXPECT_EQ(run.lists.stats.triangles_rasterized, 1);
  for (int64_t t = 0; t < run.lists.tile_count(); ++t)
    for (const TileEntry& e : test::tile_entries(run.lists, t)) EXPECT_EQ(e.triangle, 0u);
}

TEST(RasterParity, CpuAndCudaListsAreIdentical) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  const MixedScene scene;
  const test::RasterRun cpu = test::rasterize(Backend::cpu, scene.soup, scene.projection());
  const test::RasterRun gpu = test::rasterize(Backend::cuda, scene.soup, scene.projection());
  EXPECT_EQ(cpu.lists.offsets.to_vector(), gpu.lists.offsets.to_vector());
  const std::vector<TileEntry> a = cpu.lists.entries.to_vector(), b = gpu.lists.entries.to_vector();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].triangle, b[k].triangle) << "entry " << k;
    ASSERT_EQ(a[k].mask, b[k].mask) << "entry " << k;
  }
  EXPECT_EQ(cpu.counts, gpu.counts);
  nlohmann::json sc = cpu.lists.stats, sg = gpu.lists.stats;
  EXPECT_EQ(sc, sg);
}

TEST(RasterProjectionTest, PixelRaysMatchTheReferenceCamera) {
  const Camera camera = test::test_camera({1.0, 2.0, 4.0}, {-0.5, 0.3, 0.1}, 64, 48, 0.05);
  const RasterProjection p = make_camera_projection(camera, 50.0);
  const CameraView cv = make_camera_view(camera);
  for (const auto& [x, y] :
       std::vector<std::pair<int, int>>{{0, 0}, {63, 47}, {10, 30}, {31, 24}}) {
    const PixelRay ray = pixel_ray(p, x, y);
    const dvec3 want = camera_ray_direction(cv, x, y);
    EXPECT_NEAR(glm::length(ray.direction - want), 0.0, 1e-12) << x << ", " << y;
    EXPECT_NEAR(glm::length(ray.origin - camera.position), 0.0, 1e-12);
    const dvec2 pixel = test::reference_pixel(cv, ray.origin + 3.0 * ray.direction);
    EXPECT_NEAR(pixel.x, x + 0.5, 1e-9);
    EXPECT_NEAR(pixel.y, y + 0.5, 1e-9);
  }
}

TEST(RasterProjectionTest, LightViewsPlaceFrustumEdgesOnTheImageBorder) {
  const dvec3 eye(0.0, 5.0, 0.0), down(0.0, -1.0, 0.0);
  const RasterProjection persp =
      make_perspective_projection(eye, down, {0.0, 0.0, -1.0}, 60.0, 2.0, 0.5, 20.0, 128, 64);
  const double half_h = std::tan(glm::radians(30.0));
  // Looking down with up hint -z: right is +x, image up is -z.
  const PixelRay corner = pixel_ray(persp, 127, 0);  // the top-right pixel
  const dvec3 along = corner.direction / glm::dot(corner.direction, down);
  EXPECT_NEAR(along.x, 2.0 * half_h * (1.0 - 1.0 / 128.0), 1e-12);
  EXPECT_NEAR(along.z, -half_h * (1.0 - 1.0 / 64.0), 1e-12);
  const dvec4 on_near = world_to_clip_point(persp, eye + 0.5 * down);
  EXPECT_NEAR(near_plane_distance(persp, on_near), 0.0, 1e-12);
  EXPECT_NEAR(on_near.z / on_near.w, -1.0, 1e-12);

  const RasterProjection ortho =
      make_orthographic_projection(eye, down, {0.0, 0.0, -1.0}, 3.0, 1.5, 1.0, 9.0, 60, 30);
  const PixelRay ray = pixel_ray(ortho, 0, 29);
  EXPECT_NEAR(glm::length(ray.direction - down), 0.0, 1e-12);
  EXPECT_NEAR(ray.origin.y, 4.0, 1e-12);                        // on the near plane
  EXPECT_NEAR(ray.origin.x, -3.0 * (1.0 - 1.0 / 60.0), 1e-12);  // left
  EXPECT_NEAR(ray.origin.z, 1.5 * (1.0 - 1.0 / 30.0), 1e-12);   // bottom: +z
  EXPECT_GE(near_plane_distance(ortho, world_to_clip_point(ortho, eye + 1.0001 * down)), 0.0);
  EXPECT_LT(near_plane_distance(ortho, world_to_clip_point(ortho, eye + 0.9999 * down)), 0.0);
}

TEST(RasterProjectionTest, FittedFarPlaneReachesTheFarthestCorner) {
  Aabb box;
  box.extend(dvec3(-1.0, -1.0, -1.0));
  box.extend(dvec3(1.0, 1.0, 1.0));
  const double far = fit_far_plane({0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}, box, 0.1);
  EXPECT_GE(far, 6.0);
  EXPECT_LT(far, 6.001);
  EXPECT_EQ(fit_far_plane({0.0, 0.0, 5.0}, {0.0, 0.0, 1.0}, box, 0.1), 0.2);  // box behind
}

TEST(RasterProjectionTest, BadParametersAreInputErrors) {
  const dvec3 eye(0.0), dir(0.0, 0.0, -1.0), up(0.0, 1.0, 0.0);
  EXPECT_THROW(make_screen_projection(0, 10), InputError);
  EXPECT_THROW(make_screen_projection(10, kMaxRasterSide + 1), InputError);
  EXPECT_THROW(make_perspective_projection(eye, dir, up, 180.0, 1.0, 0.1, 10.0, 8, 8), InputError);
  EXPECT_THROW(make_perspective_projection(eye, dir, up, 60.0, 1.0, 0.0, 10.0, 8, 8), InputError);
  EXPECT_THROW(make_perspective_projection(eye, dir, up, 60.0, 1.0, 1.0, 0.5, 8, 8), InputError);
  EXPECT_THROW(make_perspective_projection(eye, dvec3(0.0), up, 60.0, 1.0, 0.1, 10.0, 8, 8),
               InputError);
  EXPECT_THROW(make_orthographic_projection(eye, dir, up, 0.0, 1.0, 0.1, 10.0, 8, 8), InputError);
  Camera camera;
  camera.near_plane = -1.0;
  EXPECT_THROW(make_camera_projection(camera, 10.0), InputError);
  RasterOptions options;
  options.max_entries = -1;
  EXPECT_THROW(
      rasterize_tiles(Backend::cpu, RasterView{make_screen_projection(8, 8), {}, {}}, options),
      InputError);
}

TEST(RasterStatsTest, JsonNamesEveryCounter) {
  RasterStats s;
  s.triangles_in = 7;
  s.overflow = true;
  const nlohmann::json j = s;
  EXPECT_EQ(j.at("triangles_in"), 7);
  EXPECT_EQ(j.at("overflow"), true);
  for (const char* key : {"triangles_clipped", "triangles_culled", "entries",
                          "max_entries_per_tile", "entries_needed", "dropped_tiles", "pieces"})
    EXPECT_TRUE(j.contains(key)) << key;
}

INSTANTIATE_TEST_SUITE_P(Backends, TileListsTest, ::testing::Values(Backend::cpu, Backend::cuda),
                         test::backend_name);

}  // namespace
}  // namespace dv
