// Tests of engine/scene/mesh_topology: open edges, closedness, signed volume, orientation, vertex
// merging and hole filling (on small shapes and on the shared bunny scan with its base cut off).
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "engine/scene/mesh_topology.h"
#include "experiments/source_paths.h"
#include "render/io/mesh_io.h"
#include "render/load/mesh_generators.h"

namespace dv {
namespace {

const std::string kBunnyPath =
    test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";

TriangleMesh inverted(TriangleMesh mesh) {
  for (u32vec3& t : mesh.triangles) std::swap(t.y, t.z);
  return mesh;
}

TEST(MeshTopology, QuadHasFourBoundaryEdgesInOrder) {
  const TriangleMesh quad = make_quad(1.0);
  const std::vector<OpenEdge> open = open_edges(quad);
  ASSERT_EQ(open.size(), 4u);
  for (size_t i = 0; i < open.size(); ++i) {
    EXPECT_LT(open[i].a, open[i].b);
    if (i > 0) {
      EXPECT_TRUE(open[i - 1].a < open[i].a ||
                  (open[i - 1].a == open[i].a && open[i - 1].b < open[i].b));
    }
  }
  EXPECT_FALSE(is_closed(quad));
}

TEST(MeshTopology, BoxMissingOneTriangleHasThreeOpenEdges) {
  TriangleMesh box = make_box(dvec3(0.0), dvec3(1.0));
  EXPECT_TRUE(open_edges(box).empty());
  EXPECT_TRUE(is_closed(box));
  const u32vec3 removed = box.triangles[5];
  box.triangles.erase(box.triangles.begin() + 5);
  const std::vector<OpenEdge> open = open_edges(box);
  ASSERT_EQ(open.size(), 3u);
  auto in_removed = [&](uint32_t v) { return v == removed.x || v == removed.y || v == removed.z; };
  for (const OpenEdge& e : open)
    EXPECT_TRUE(in_removed(e.a) && in_removed(e.b)) << e.a << "-" << e.b;
  EXPECT_FALSE(is_closed(box));
}

TEST(MeshTopology, EdgeUsedThreeTimesIsOpen) {
  TriangleMesh fan;
  fan.positions = {dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1)};
  fan.triangles = {u32vec3(0, 1, 2), u32vec3(1, 0, 3), u32vec3(0, 1, 4)};
  const std::vector<OpenEdge> open = open_edges(fan);
  EXPECT_TRUE(std::any_of(open.begin(), open.end(),
                          [](const OpenEdge& e) { return e.a == 0 && e.b == 1; }));
  EXPECT_EQ(open.size(), 7u);  // 0-1 three times, plus the 6 single edges
}

TEST(MeshTopology, EmptyMeshIsNotClosed) {
  EXPECT_FALSE(is_closed(TriangleMesh{}));
}

TEST(MeshTopology, SignedVolumeOfBoxIsExactAndFlipsSign) {
  const TriangleMesh box = make_box(dvec3(-1.0, 0.5, 2.0), dvec3(2.0, 1.5, 4.5));
  EXPECT_NEAR(signed_volume(box), 3.0 * 1.0 * 2.5, 1e-12);
  EXPECT_NEAR(signed_volume(inverted(box)), -7.5, 1e-12);
}

TEST(MeshTopology, SignedVolumeRejectsIndexOutOfRange) {
  TriangleMesh bad = make_box(dvec3(0.0), dvec3(1.0));
  bad.triangles[0].z = 99;
  EXPECT_THROW(signed_volume(bad), InputError);
}

TEST(MeshTopology, OrientOutwardFlipsAnInvertedBox) {
  TriangleMesh box = inverted(make_box(dvec3(0.0), dvec3(2.0)));
  ASSERT_LT(signed_volume(box), 0.0);
  orient_outward(box);
  EXPECT_TRUE(is_closed(box));
  EXPECT_NEAR(signed_volume(box), 8.0, 1e-12);
  EXPECT_EQ(box.triangles.size(), 12u);
}

TEST(MeshTopology, OrientOutwardRepairsMixedWinding) {
  TriangleMesh sphere = make_icosphere(1.0, 2);
  const double volume = signed_volume(sphere);
  for (size_t t = 0; t < sphere.triangles.size(); t += 3)
    std::swap(sphere.triangles[t].y, sphere.triangles[t].z);
  orient_outward(sphere);
  EXPECT_TRUE(is_closed(sphere));
  EXPECT_NEAR(signed_volume(sphere), volume, 1e-9);
}

TEST(MeshTopology, OrientOutwardKeepsInnerShellOfHollowSolidInward) {
  TriangleMesh shell = make_box(dvec3(-2.0), dvec3(2.0));
  const TriangleMesh inner = make_box(dvec3(-1.0), dvec3(1.0));  // wrongly outward
  const uint32_t offset = uint32_t(shell.positions.size());
  shell.positions.insert(shell.positions.end(), inner.positions.begin(), inner.positions.end());
  for (const u32vec3& t : inner.triangles) shell.triangles.push_back(t + offset);
  orient_outward(shell);
  EXPECT_NEAR(signed_volume(shell), 64.0 - 8.0, 1e-9);
}

TEST(MeshTopology, MergeDuplicateVerticesJoinsSoupIntoClosedBox) {
  const TriangleMesh box = make_box(dvec3(0.0), dvec3(1.0));
  TriangleMesh soup;
  for (const u32vec3& t : box.triangles) {
    const uint32_t base = uint32_t(soup.positions.size());
    for (int k = 0; k < 3; ++k) soup.positions.push_back(box.positions[t[k]]);
    soup.triangles.emplace_back(base, base + 1, base + 2);
  }
  ASSERT_EQ(open_edges(soup).size(), 36u);
  merge_duplicate_vertices(soup);
  EXPECT_EQ(soup.positions.size(), 8u);
  EXPECT_EQ(soup.triangles.size(), 12u);
  EXPECT_TRUE(is_closed(soup));
  EXPECT_NEAR(signed_volume(soup), 1.0, 1e-12);
}

TEST(MeshTopology, MergeDropsTrianglesThatCollapse) {
  TriangleMesh mesh;
  mesh.positions = {dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)};
  mesh.triangles = {u32vec3(0, 1, 2), u32vec3(0, 2, 3)};
  merge_duplicate_vertices(mesh);
  EXPECT_EQ(mesh.positions.size(), 3u);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], u32vec3(0, 1, 2));
}

TEST(MeshTopology, CloseHolesFillsABoxWithMissingTriangles) {
  TriangleMesh box = make_box(dvec3(0.0), dvec3(1.0));
  box.triangles.erase(box.triangles.begin() + 6, box.triangles.begin() + 8);  // the -y face
  ASSERT_EQ(open_edges(box).size(), 4u);
  close_holes(box);
  EXPECT_TRUE(is_closed(box));
  EXPECT_GT(signed_volume(box), 0.5);
}

TEST(MeshTopology, CloseHolesOfAnEmptyMeshThrows) {
  TriangleMesh empty;
  EXPECT_THROW(close_holes(empty), Error);
}

TEST(MeshTopology, SharedBunnyIsClosedAsShipped) {
  TriangleMesh bunny = load_mesh_file(kBunnyPath);
  EXPECT_EQ(bunny.triangles.size(), 3674u);
  EXPECT_EQ(bunny.positions.size(), 1839u);
  EXPECT_TRUE(is_closed(bunny));
  const double volume = signed_volume(bunny);
  EXPECT_GT(volume, 0.0);
  close_holes(bunny);  // nothing to fill: the mesh must come back unchanged in size
  EXPECT_EQ(bunny.triangles.size(), 3674u);
  EXPECT_NEAR(signed_volume(bunny), volume, 1e-9 * volume);
}

TEST(MeshTopology, BunnyWithItsBaseCutOffIsClosedAgain) {
  TriangleMesh bunny = load_mesh_file(kBunnyPath);
  const double full_volume = signed_volume(bunny);
  // Remove every triangle with a corner near the bottom, like a scan that missed the base.
  std::erase_if(bunny.triangles, [&](const u32vec3& t) {
    return bunny.positions[t.x].y < 0.3 || bunny.positions[t.y].y < 0.3 ||
           bunny.positions[t.z].y < 0.3;
  });
  ASSERT_FALSE(is_closed(bunny));
  ASSERT_LT(bunny.triangles.size(), 3674u);
  close_holes(bunny);
  EXPECT_TRUE(is_closed(bunny));
  const double volume = signed_volume(bunny);
  EXPECT_GT(volume, 0.8 * full_volume);
  EXPECT_LT(volume, 1.2 * full_volume);
}

}  // namespace
}  // namespace dv
