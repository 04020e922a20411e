// The viewer's overlays without a window: the error view (E) is |T' - T| at each pixel's
// visible surface, equal to an independent computation through `deepvox probe`; the voxel grid
// overlay (G) holds one point per set voxel of the transmittance slicemap's grids, each inside
// its voxel.
#include <gtest/gtest.h>

#include <cmath>

#include "apps/viewer/viewer_state.h"
#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/apps/viewer/viewer_test_support.h"
#include "tests/support/scratch_dir.h"

namespace dv::viewer {
namespace {

const std::string kScene = test::source_dir() + "/experiments/scenes/translucent-boxes.json";

ViewerSetup small_setup(const std::string& method) {
  ViewerSetup s;
  s.scene_path = kScene;
  s.backend = "cpu";
  s.width = 48;
  s.height = 32;
  s.shadows.name = method;
  return s;
}

TEST(ViewerErrorView, EqualsAnIndependentProbeOfTheVisibleSurface) {
  ViewerSetup setup = small_setup("dsm");
  setup.shadows.dsm_res = 64;
  ViewerState state(setup);
  state.drag(40.0, -12.0, MouseButton::left);  // an orbited camera, as render --view
  EXPECT_EQ(state.error_view(), nullptr);
  state.key("E");
  ASSERT_TRUE(state.update());
  const TransmittanceError* e = state.error_view();
  ASSERT_NE(e, nullptr);
  EXPECT_GT(e->max, 0.0);  // dsm at res 64 is not the oracle
  EXPECT_EQ(state.stats()["error_view"]["max"].get<double>(), e->max);

  Scene scene = load_scene(kScene);
  scene.camera.width = 48;
  scene.camera.height = 32;
  const Camera camera = moved_camera(scene.camera, {-10.0, -3.0, 1.0, 0.0, 0.0});
  const test::IndependentError ref = test::independent_error(
      kScene, scene, camera, "--shadows dsm --dsm-res 64", test::scratch_dir("test_viewer"));
  ASSERT_TRUE(ref.failure.empty()) << ref.failure;
  ASSERT_EQ(e->error.size(), ref.error.size());
  EXPECT_EQ(e->pixels, ref.pixels);
  int differing = 0;
  for (size_t i = 0; i < ref.error.size(); ++i) {
    ASSERT_EQ(std::isnan(e->error[i]), std::isnan(ref.error[i])) << "pixel " << i;
    if (!std::isnan(ref.error[i]) && std::abs(e->error[i] - ref.error[i]) > 1e-9) ++differing;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_NEAR(e->max, ref.max, 1e-9);
  EXPECT_NEAR(e->mean, ref.mean, 1e-9);
  std::printf("error view, dsm res 64, 48x32: max %.6g mean %.6g over %lld pixels\n", e->max,
              e->mean, static_cast<long long>(e->pixels));

  // The display is the colour map (the rendered image stays render's), and back without E.
  EXPECT_NE(state.display().rgb, state.image().rgb);
  state.key("E");
  state.update();
  EXPECT_EQ(state.error_view(), nullptr);
  // The rendered image through the display transform (render's default tone curve, aces).
  EXPECT_EQ(state.display().rgb,
            apply_display_transform(state.image(), state.display_transform()).rgb);
}

TEST(ViewerErrorView, ReferenceAgainstItselfIsZero) {
  ViewerState state(small_setup("reference"));
  state.key("E");
  state.update();
  ASSERT_NE(state.error_view(), nullptr);
  EXPECT_GT(state.error_view()->pixels, 0);
  EXPECT_EQ(state.error_view()->max, 0.0);
}

TEST(ViewerVoxelOverlay, OnePointPerSetVoxelInsideItsVoxel) {
  ViewerSetup setup = small_setup("transmittance-slicemap");
  setup.shadows.params = {"res=64"};
  ViewerState state(setup);
  state.key("G");
  state.update();
  const VoxelPoints* points = state.voxel_points();
  ASSERT_NE(points, nullptr);
  const int64_t set_voxels = state.stats()["shadows"]["stats"]["set_voxels"].get<int64_t>();
  EXPECT_GT(set_voxels, 0);
  EXPECT_EQ(points->count(), set_voxels);
  EXPECT_EQ(points->positions.size(), size_t(points->count()) * 3);

  // Every centre lies in the middle of a set voxel of the method's grid (grid_transform, the
  // lookup's own mapping), to float precision of the stored position.
  auto method =
      shadow_registry().create("transmittance-slicemap", StrategyParams::parse({"res=64"}));
  const Scene scene = load_scene(kScene);
  const SceneData data(scene, Memory::host);
  method->prepare(data, Backend::cpu, nullptr);
  const std::vector<VoxelGrid>* grids = method->voxel_grids();
  ASSERT_NE(grids, nullptr);
  ASSERT_EQ(int(grids->size()), points->grids);
  const GridSpec& spec = grids->front().spec();
  const GridTransform t = grid_transform(spec);
  int checked = 0;
  for (int z = 0; z < spec.res.z; ++z)
    for (int y = 0; y < spec.res.y; ++y)
      for (int x = 0; x < spec.res.x; ++x) {
        if (!grids->front().get(x, y, z)) continue;
        const dvec3 g = t.apply(voxel_centre(spec, x, y, z));
        ASSERT_NEAR(g.x, x + 0.5, 1e-6);
        ASSERT_NEAR(g.y, y + 0.5, 1e-6);
        ASSERT_NEAR(g.z, z + 0.5, 1e-6);
        ++checked;
      }
  EXPECT_GT(checked, 0);

  state.key("G");
  EXPECT_EQ(state.voxel_points(), nullptr);
}

TEST(ViewerVoxelOverlay, MethodWithoutGridsIsAMessage) {
  ViewerState state(small_setup("shadowmap"));
  state.update();
  state.key("G");
  state.update();
  EXPECT_EQ(state.voxel_points(), nullptr);
  EXPECT_NE(state.message().find("has no voxel grids"), std::string::npos) << state.message();
}

}  // namespace
}  // namespace dv::viewer
