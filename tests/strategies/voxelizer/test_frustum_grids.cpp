// Voxel grids over light frustums (frustum_grid.h): the grid transform against the face's
// pixel rays, the point methods (slicemap, atlas, atlas-compute) putting a quad facing a spot
// light into its one slice and the columns it covers, the conservative methods (sat, exact)
// agreeing on an orthographic grid and rejecting perspective ones, and no MIP levels there.
#include <gtest/gtest.h>

#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/frustum_grid.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/voxelizer.h"
#include "tests/strategies/voxelizer/voxel_test_support.h"
#include "tests/support/light_face_cases.h"

namespace dv {
namespace {

using test::spot_face;
using test::sun_face;

// A 1.2-wide horizontal quad at height y.
TriangleSoup quad_at(double y) {
  dmat4 m(1.0);
  m[3] = dvec4(0.1, y, -0.05, 1.0);
  return triangle_soup(make_quad(1.2), m);
}

TEST(FrustumGrid, TransformFollowsThePixelRays) {
  const ShadowFace face = spot_face(64);
  const GridSpec spec = make_light_grid(face, 64, 32, Aabb{dvec3(-1, 0.5, -1), dvec3(1, 1.5, 1)});
  EXPECT_EQ(spec.kind, GridKind::perspective);
  const GridTransform t = grid_transform(spec);
  const PixelRay ray = image_point_ray(spec.frustum.projection, 20.3, 41.6);
  const double axial = 3.0;  // 1 above the floor
  const dvec3 p = ray.origin + ray.direction * (axial / glm::dot(ray.direction, face.axis));
  const dvec3 g = t.apply(p);
  EXPECT_NEAR(g.x, 20.3, 1e-9);
  EXPECT_NEAR(g.y, 41.6, 1e-9);
  EXPECT_NEAR(g.z, (axial - spec.frustum.near) / (spec.frustum.far - spec.frustum.near) * 32, 1e-9);
  EXPECT_TRUE(std::isnan(t.apply(dvec3(0.0, 5.0, 0.0)).x));  // behind the light
  EXPECT_THROW(mip_down(VoxelGrid(spec, Memory::host)), InputError);
}

TEST(FrustumGrid, PointMethodsPutAFacingQuadIntoItsSlice) {
  const ShadowFace face = spot_face(48);
  const TriangleSoup soup = quad_at(1.0);
  // Casters from y = 0.5 to 2: the quad (axial depth 3) sits at z = (3 - 2) / 1.5 * 64.
  const GridSpec spec = make_light_grid(face, 48, 64, Aabb{dvec3(-1, 0.5, -1), dvec3(1, 2, 1)});
  const int slice = int((3.0 - spec.frustum.near) * 64 / (spec.frustum.far - spec.frustum.near));
  test::VoxelSet expected_columns;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const PixelRay r = pixel_ray(spec.frustum.projection, x, y);
      const dvec3 hit = r.origin + r.direction * (3.0 / -r.direction.y);
      if (std::abs(hit.x - 0.1) < 0.6 && std::abs(hit.z + 0.05) < 0.6)
        expected_columns.insert({x, y, slice});
    }
  for (const char* name : {"slicemap", "atlas", "atlas-compute"}) {
    auto v = voxelizer_registry().create(name);
    const VoxelizeResult r = v->voxelize(Backend::cpu, soup, spec);
    const test::VoxelSet got = test::voxels_of(r.grid);
    for (const auto& [x, y, z] : got) EXPECT_EQ(z, slice) << name;
    if (std::string(name) == "slicemap") {
      EXPECT_EQ(got, expected_columns);
    } else {
      for (const auto& voxel : expected_columns) EXPECT_TRUE(got.count(voxel)) << name;
      EXPECT_LE(got.size(), expected_columns.size() + 4 * 48) << name;  // edge columns
    }
  }
}

TEST(FrustumGrid, ConservativeMethodsAgreeOnOrthographicGridsAndRejectPerspective) {
  dmat4 m(1.0);
  m[3] = dvec4(0.2, 1.0, -0.1, 1.0);
  const TriangleSoup ball = triangle_soup(make_icosphere(0.7, 2), m);
  const GridSpec ortho = make_light_grid(sun_face(40), 40, 32, ball.bounds());
  EXPECT_EQ(ortho.kind, GridKind::orthographic);
  const ExactVoxelization exact = voxelize_exact(ball, ortho, true);
  const VoxelizeResult sat =
      voxelizer_registry().create("sat")->voxelize(Backend::cpu, ball, ortho);
  const VoxelMetrics metrics = compare_with_exact(sat.grid, exact);
  EXPECT_GT(metrics.reference_filled, 500);
  EXPECT_EQ(metrics.missing_outside_band, 0);
  EXPECT_EQ(metrics.extra_outside_band, 0);

  const GridSpec persp = make_light_grid(spot_face(40), 40, 32, ball.bounds());
  for (const char* name : {"sat", "exact"}) {
    try {
      voxelizer_registry().create(name)->voxelize(Backend::cpu, ball, persp);
      ADD_FAILURE() << name << " accepted a perspective grid";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("perspective"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace dv
