// Coverage of the tile rasterizer against independent references, on every backend: planar
// meshes cover each pixel centre inside their outline exactly once, a closed sphere exactly
// twice with no silhouette cracks, the top-left rule decides centres on edges and vertices,
// degenerate triangles cover nothing, huge ones cover all without overflow, the near plane
// clips exactly and triangles behind it are culled.
#include <random>

#include "render/load/mesh_generators.h"
#include "tests/engine/raster/raster_test_support.h"

namespace dv {
namespace {

class Coverage : public test::RasterBackendTest {};
using test::Side;

dmat4 odd_rotation() {
  dmat4 m = glm::rotate(dmat4(1.0), glm::radians(68.0), dvec3(1.0, 0.0, 0.0));
  m = glm::rotate(m, glm::radians(27.0), dvec3(0.0, 0.0, 1.0));
  return glm::rotate(m, glm::radians(13.0), dvec3(0.0, 1.0, 0.0));
}

// Compares the per-pixel counts with `expected` (reference counts, -1 where ambiguous).
void expect_counts(const test::RasterRun& run, const std::vector<int>& expected) {
  int mismatches = 0;
  for (int y = 0; y < run.height; ++y)
    for (int x = 0; x < run.width; ++x) {
      const int want = expected[size_t(y) * run.width + x];
      if (want >= 0 && int(run.count(x, y)) != want && ++mismatches <= 10)
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << run.count(x, y)
                      << " fragments, reference " << want;
    }
  EXPECT_EQ(mismatches, 0);
}

TEST_P(Coverage, SubdividedQuadCoversItsOutlineExactlyOnce) {
  const Camera camera = test::test_camera({0.1, -0.05, 3.0}, {0.0, 0.0, 0.0}, 203, 149);
  const dmat4 placement = odd_rotation();
  test::Soup soup;
  soup.add(make_subdivided_quad(2.6, 1800), placement);
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_camera_projection(camera, 10.0));
  const CameraView cv = make_camera_view(camera);
  std::vector<dvec3> outline;
  for (const dvec2 corner : {dvec2(-1, -1), dvec2(1, -1), dvec2(1, 1), dvec2(-1, 1)})
    outline.push_back(dvec3(placement * dvec4(1.3 * corner.x, 0.0, 1.3 * corner.y, 1.0)));
  const std::vector<dvec2> projected = test::project_polygon(cv, outline);
  std::vector<int> expected(size_t(camera.width) * camera.height);
  int inside = 0, outside = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Side side = test::classify(projected, test::pixel_center(x, y));
      expected[size_t(y) * camera.width + x] = side == Side::inside    ? 1
                                               : side == Side::outside ? 0
                                                                       : -1;
      inside += side == Side::inside;
      outside += side == Side::outside;
      EXPECT_LE(run.count(x, y), 1u) << "pixel (" << x << ", " << y << ") covered twice";
    }
  expect_counts(run, expected);
  EXPECT_GT(inside, camera.width * camera.height / 3);  // the outline crosses the image
  EXPECT_GT(outside, camera.width * camera.height / 20);
  EXPECT_EQ(run.lists.stats.triangles_in, int64_t(soup.triangles.size()));
  EXPECT_EQ(run.lists.stats.triangles_culled + run.lists.stats.triangles_rasterized,
            run.lists.stats.triangles_in);
}

TEST_P(Coverage, ClosedSphereCoversEveryPixelTwiceWithoutCracks) {
  const Camera camera = test::test_camera({0.4, 0.3, 2.6}, {0.05, -0.04, 0.0}, 160, 120);
  test::Soup soup;
  soup.add(make_icosphere(0.8, 3));
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_camera_projection(camera, 10.0));
  const CameraView cv = make_camera_view(camera);
  std::vector<std::vector<dvec2>> projected;
  for (const u32vec3& t : soup.triangles)
    projected.push_back(
        test::project_polygon(cv, {soup.vertices[t.x], soup.vertices[t.y], soup.vertices[t.z]}));
  std::vector<int> expected(size_t(camera.width) * camera.height);
  int covered = 0, ambiguous = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      int count = 0;
      bool unsure = false;
      for (const auto& tri : projected) {
        const Side side = test::classify(tri, test::pixel_center(x, y));
        count += side == Side::inside;
        unsure |= side == Side::ambiguous;
      }
      expected[size_t(y) * camera.width + x] = unsure ? -1 : count;
      ambiguous += unsure;
      covered += run.count(x, y) > 0;
      EXPECT_TRUE(run.count(x, y) == 0 || run.count(x, y) == 2)
          << "pixel (" << x << ", " << y << "): " << run.count(x, y) << " fragments";
    }
  expect_counts(run, expected);
  EXPECT_GT(covered, camera.width * camera.height / 4);
  EXPECT_LT(ambiguous, camera.width * camera.height / 100);
}

// A rectangle of pixel-centre-aligned vertices, jittered by whole pixels and triangulated with
// random windings: many edges and vertices pass exactly through pixel centres.
TEST_P(Coverage, JitteredGridOnPixelCentresIsWatertight) {
  const int width = 70, height = 53, cells_x = 15, cells_y = 11, spacing = 4;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> jitter(-1, 1);
  test::Soup soup;
  for (int j = 0; j <= cells_y; ++j)
    for (int i = 0; i <= cells_x; ++i) {
      const bool border_x = i == 0 || i == cells_x, border_y = j == 0 || j == cells_y;
      const double x = 3.5 + spacing * i + (border_x ? 0 : jitter(rng));
      const double y = 2.5 + spacing * j + (border_y ? 0 : jitter(rng));
      soup.vertices.push_back({x, y, 0.0});
    }
  std::bernoulli_distribution coin(0.5);
  for (int j = 0; j < cells_y; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const uint32_t a = j * (cells_x + 1) + i, b = a + 1, c = a + cells_x + 1, d = c + 1;
      for (u32vec3 t : coin(rng) ? std::vector<u32vec3>{{a, b, d}, {a, d, c}}
                                 : std::vector<u32vec3>{{a, b, c}, {b, d, c}}) {
        if (coin(rng)) std::swap(t.y, t.z);
        soup.triangles.push_back(t);
      }
    }
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_screen_projection(width, height));
  // Outline [3.5, 63.5] x [2.5, 46.5]: centres on the top and left sides are inside.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool inside = x >= 3 && x < 63 && y >= 2 && y < 46;
      EXPECT_EQ(run.count(x, y), inside ? 1u : 0u) << "pixel (" << x << ", " << y << ")";
    }
  EXPECT_EQ(run.lists.stats.triangles_rasterized, int64_t(soup.triangles.size()));
}

TEST_P(Coverage, TopLeftRuleOnEdgesThroughPixelCentres) {
  // The square [2.5, 10.5]^2 split along its diagonal; triangle 0 is the upper-right half.
  test::Soup soup;
  soup.add_triangle({2.5, 2.5, 0}, {10.5, 2.5, 0}, {10.5, 10.5, 0});
  soup.add_triangle({2.5, 2.5, 0}, {2.5, 10.5, 0}, {10.5, 10.5, 0});  // other winding
  // A horizontal bottom edge through centres (excluded) and a top one (included).
  soup.add_triangle({13.5, 2.5, 0}, {20.5, 8.5, 0}, {13.5, 8.5, 0});
  soup.add_triangle({13.5, 10.5, 0}, {20.5, 10.5, 0}, {13.5, 14.5, 0});
  const test::RasterRun run = test::rasterize(backend(), soup, make_screen_projection(24, 16));
  const TileListsView v = run.lists.view();
  auto owners = [&](int x, int y) {
    std::vector<uint32_t> ids;
    for_each_fragment(v, x, y, [&ids](uint32_t id) { ids.push_back(id); });
    return ids;
  };
  using Ids = std::vector<uint32_t>;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const bool in_square = x >= 2 && x < 10 && y >= 2 && y < 10;  // top and left sides only
      Ids want;
      if (in_square) want = {x >= y ? 0u : 1u};  // the diagonal is a left edge of triangle 0
      EXPECT_EQ(owners(x, y), want) << "pixel (" << x << ", " << y << ")";
    }
  EXPECT_EQ(owners(13, 5), Ids{2});  // left edge
  EXPECT_EQ(owners(14, 8), Ids{});   // bottom edge y = 8.5
  EXPECT_EQ(owners(14, 7), Ids{2});
  EXPECT_EQ(owners(14, 10), Ids{3});  // top edge y = 10.5
  EXPECT_EQ(owners(19, 10), Ids{3});
  EXPECT_EQ(owners(20, 10), Ids{});  // the top edge's right end lies on the slanted edge
  EXPECT_EQ(owners(13, 14), Ids{});  // bottom vertex
}

TEST_P(Coverage, FanAroundAPixelCentreCoversItOnce) {
  test::Soup soup;
  const dvec3 centre(8.5, 8.5, 0.0);
  const dvec3 ring[8] = {{14.5, 8.5, 0}, {12.5, 13.5, 0}, {8.5, 14.5, 0}, {3.5, 12.5, 0},
                         {2.5, 8.5, 0},  {4.5, 3.5, 0},   {8.5, 2.5, 0},  {13.5, 4.5, 0}};
  for (int k = 0; k < 8; ++k) soup.add_triangle(centre, ring[k], ring[(k + 1) % 8]);
  const test::RasterRun run = test::rasterize(backend(), soup, make_screen_projection(17, 17));
  EXPECT_EQ(run.count(8, 8), 1u);
  std::vector<dvec2> outline;
  for (const dvec3& p : ring) outline.push_back({p.x, p.y});
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 17; ++x) {
      EXPECT_LE(run.count(x, y), 1u) << "pixel (" << x << ", " << y << ")";
      if (test::classify(outline, test::pixel_center(x, y)) == Side::inside) {
        EXPECT_EQ(run.count(x, y), 1u) << "pixel (" << x << ", " << y << ")";
      }
    }
}

TEST_P(Coverage, DegenerateTrianglesCoverNothing) {
  test::Soup soup;
  soup.add_triangle({1.5, 1.5, 0}, {5.5, 3.5, 0}, {9.5, 5.5, 0});        // collinear
  soup.add_triangle({2.0, 7.0, 0}, {2.0, 7.0, 0}, {12.0, 9.0, 0});       // repeated vertex
  soup.add_triangle({4.0, 4.0, 0}, {4.0, 4.0, 0}, {4.0, 4.0, 0});        // a point
  soup.add_triangle({6.5, 6.5, 0}, {6.5001, 6.5, 0}, {6.5, 6.5001, 0});  // zero after snapping
  const test::RasterRun run = test::rasterize(backend(), soup, make_screen_projection(16, 16));
  for (uint32_t c : run.counts) EXPECT_EQ(c, 0u);
  EXPECT_EQ(run.lists.stats.culled_degenerate, 4);
  EXPECT_EQ(run.lists.stats.triangles_culled, 4);
  EXPECT_EQ(run.lists.stats.entries, 0);
}

TEST_P(Coverage, HugeTriangleCoversTheImageWithoutOverflow) {
  const Camera camera = test::test_camera({0.0, 0.0, 5.0}, {0.3, 0.1, 0.0}, 97, 64);
  test::Soup soup;
  soup.add_triangle({-1e6, -1e6, 0.0}, {1e6, -1e6, 0.0}, {0.0, 1e6, 0.0});
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_camera_projection(camera, 100.0));
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) EXPECT_EQ(run.count(x, y), 1u) << x << ", " << y;
  EXPECT_EQ(run.lists.stats.clipped_guard, 1);
  EXPECT_EQ(run.lists.stats.entries_needed, run.lists.stats.entries);
  for (int64_t t = 0; t < run.lists.tile_count(); ++t) {
    const std::vector<TileEntry> entries = test::tile_entries(run.lists, t);
    EXPECT_FALSE(entries.empty()) << "tile " << t;
    for (const TileEntry& e : entries) EXPECT_EQ(e.triangle, 0u);
  }
}

// A floor of three huge triangles through the eye's level: near plane and guard band at once.
TEST_P(Coverage, HugeFloorCrossingTheNearPlaneMatchesTheClippedPolygon) {
  const Camera camera = test::test_camera({0.0, 0.0, 0.0}, {0.2, -0.3, -1.0}, 120, 90, 0.05);
  test::Soup soup;
  const std::vector<std::vector<dvec3>> floor = {
      {{-1e6, -1.0, 1e6}, {1e6, -1.0, 1e6}, {0.0, -1.0, -1e6}},
      {{0.0, -1.0, -1e6}, {1e6, -1.0, 1e6}, {3e6, -1.0, -2e6}},
      {{-2e6, -1.0, -3e6}, {-1e6, -1.0, 1e6}, {0.0, -1.0, -1e6}}};
  for (const auto& t : floor) soup.add_triangle(t[0], t[1], t[2]);
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_camera_projection(camera, 10.0));
  const CameraView cv = make_camera_view(camera);
  std::vector<int> expected(size_t(camera.width) * camera.height);
  int covered = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      int count = 0;
      bool unsure = false;
      for (const auto& t : floor) {
        const Side side = test::classify(test::project_polygon(cv, t), test::pixel_center(x, y));
        count += side == Side::inside;
        unsure |= side == Side::ambiguous;
      }
      expected[size_t(y) * camera.width + x] = unsure ? -1 : count;
      covered += count > 0;
    }
  expect_counts(run, expected);
  EXPECT_GT(covered, camera.width * camera.height / 3);
  EXPECT_LT(covered, camera.width * camera.height);
  EXPECT_EQ(run.lists.stats.clipped_near, 3);
  EXPECT_GE(run.lists.stats.clipped_guard, 1);
}

TEST_P(Coverage, NearPlaneClipsExactlyAndCullsWhatIsBehind) {
  const Camera camera = test::test_camera({0.0, 0.0, 3.0}, {0.0, 0.0, 0.0}, 128, 96, 0.5);
  const std::vector<dvec3> crossing = {{-1.0, -1.0, 0.0}, {1.0, -0.5, 0.0}, {0.2, 0.8, 4.0}};
  test::Soup soup;
  soup.add_triangle(crossing[0], crossing[1], crossing[2]);
  soup.add_triangle({-1.0, -1.0, 3.6}, {1.0, 0.0, 3.6}, {0.0, 1.0, 9.0});  // behind the near plane
  const test::RasterRun run =
      test::rasterize(backend(), soup, make_camera_projection(camera, 10.0));
  const std::vector<dvec2> clipped = test::project_polygon(make_camera_view(camera), crossing);
  ASSERT_EQ(clipped.size(), 4u);
  std::vector<int> expected(size_t(camera.width) * camera.height);
  int inside = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Side side = test::classify(clipped, test::pixel_center(x, y));
      expected[size_t(y) * camera.width + x] = side == Side::inside    ? 1
                                               : side == Side::outside ? 0
                                                                       : -1;
      inside += side == Side::inside;
    }
  expect_counts(run, expected);
  EXPECT_GT(inside, 500);
  const RasterStats& s = run.lists.stats;
  EXPECT_EQ(s.clipped_near, 1);
  EXPECT_EQ(s.culled_behind, 1);
  EXPECT_EQ(s.triangles_culled, 1);
  EXPECT_EQ(s.pieces, 2);  // the clipped quadrilateral as a fan of two
  for (int64_t t = 0; t < run.lists.tile_count(); ++t)
    for (const TileEntry& e : test::tile_entries(run.lists, t)) EXPECT_EQ(e.triangle, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, Coverage, ::testing::Values(Backend::cpu, Backend::cuda),
                         test::backend_name);

}  // namespace
}  // namespace dv
