// The viewer's state without a window: key switches go through the registries (a switch the
// registry rejects leaves a message and the old state), mouse moves become the camera move that
// `render --view` replays, and the image is render_raster's for that camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "apps/viewer/viewer_state.h"
#include "cuda/buffer.h"
#include "engine/scene/scene_view.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"

namespace dv::viewer {
namespace {

ViewerSetup small_dsm_setup() {
  ViewerSetup s;
  s.scene_path = test::source_dir() + "/experiments/scenes/translucent-boxes.json";
  s.backend = "cpu";
  s.width = 48;
  s.height = 32;
  s.shadows.name = "dsm";
  s.shadows.dsm_res = 64;
  return s;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MovedCamera, YawIsOrbitPitchStopsShortOfThePoleDollyAndPanScale) {
  Camera c;
  c.position = {0.0, 1.0, 5.0};
  c.target = {0.0, 1.0, 0.0};
  EXPECT_EQ(moved_camera(c, {}).position, c.position);
  const Camera yawed = moved_camera(c, {90.0, 0.0, 1.0, 0.0, 0.0});
  const Camera orbited = orbit_camera(c, 360.0, 1, 4);
  EXPECT_NEAR(glm::length(yawed.position - orbited.position), 0.0, 1e-12);
  const Camera up = moved_camera(c, {0.0, 30.0, 1.0, 0.0, 0.0});
  EXPECT_NEAR(up.position.y - 1.0, 5.0 * std::sin(30.0 * M_PI / 180.0), 1e-12);
  const Camera top = moved_camera(c, {0.0, 120.0, 1.0, 0.0, 0.0});  // clamped at 89 degrees
  EXPECT_NEAR(top.position.y - 1.0, 5.0 * std::sin(89.0 * M_PI / 180.0), 1e-12);
  const Camera near = moved_camera(c, {0.0, 0.0, 0.5, 0.0, 0.0});
  EXPECT_NEAR(glm::length(near.position - near.target), 2.5, 1e-12);
  const Camera panned = moved_camera(c, {0.0, 0.0, 1.0, 0.1, -0.2});
  EXPECT_NEAR(panned.target.x, 0.5, 1e-12);  // right of a camera looking down -z is +x
  EXPECT_NEAR(panned.target.y, 0.0, 1e-12);
  EXPECT_NEAR(glm::length(panned.position - panned.target - (c.position - c.target)), 0.0, 1e-12);
}

TEST(ViewerState, ImageIsRenderRasterOfTheMovedCamera) {
  ViewerState state(small_dsm_setup());
  state.drag(40.0, -12.0, MouseButton::left);
  ASSERT_TRUE(state.update());
  EXPECT_FALSE(state.update());  // nothing changed since
  EXPECT_TRUE(contains(state.render_command("o.png"), " --view -10,-3,1,0,0"))
      << state.render_command("o.png");

  Scene scene = load_scene(small_dsm_setup().scene_path);
  scene.camera.width = 48;
  scene.camera.height = 32;
  const SceneData data(scene, memory_of(Backend::cpu));
  auto method = shadow_registry().create("dsm", StrategyParams::parse({"res=64"}));
  const Camera cam = moved_camera(scene.camera, {-10.0, -3.0, 1.0, 0.0, 0.0});
  const Image expected =
      render_raster(Backend::cpu, data, cam, *method, scene.background).render.image;
  ASSERT_EQ(state.image().rgb.size(), expected.rgb.size());
  EXPECT_EQ(state.image().rgb, expected.rgb);
  EXPECT_NE(cam.position, scene.camera.position);

  state.key("R");
  EXPECT_FALSE(contains(state.render_command("o.png"), "--view"));
  EXPECT_FALSE(contains(state.render_command("o.png"), "--tonemap"));  // render's default
  EXPECT_FALSE(contains(state.render_command("o.png"), "ground"));
  ViewerSetup bare = small_dsm_setup();
  bare.staging.ground = GroundPlane::off;
  EXPECT_TRUE(contains(ViewerState(bare).render_command("o.png"), " --no-ground"));
}

TEST(ViewerState, CoarseImageIsRefinedByTheNextFullUpdate) {
  ViewerState state(small_dsm_setup());
  ASSERT_TRUE(state.update());
  const std::vector<float> full = state.image().rgb;
  state.drag(4.0, 0.0, MouseButton::left);
  state.drag(-4.0, 0.0, MouseButton::left);  // back where it was
  ASSERT_TRUE(state.update(true));
  EXPECT_EQ(state.image().width, 48);
  EXPECT_EQ(state.image().height, 32);
  EXPECT_EQ(state.stats()["coarse"], 4);
  EXPECT_EQ(state.image().rgb[3 * 1], state.image().rgb[0]);  // pixels (0,0) and (1,0) are one
  EXPECT_NE(state.image().rgb, full);
  EXPECT_TRUE(state.update());  // resting: the full image again, though nothing changed
  EXPECT_EQ(state.image().rgb, full);
  EXPECT_FALSE(state.update());
}

TEST(ViewerState, SwitchesGoThroughTheRegistries) {
  ViewerState state(small_dsm_setup());
  state.key("[");
  EXPECT_TRUE(contains(state.render_command("o.png"), "--eps 0.01"))
      << state.render_command("o.png");
  state.key("-");
  EXPECT_TRUE(contains(state.render_command("o.png"), "--dsm-res 32"));
  state.key("F");
  EXPECT_TRUE(contains(state.render_command("o.png"), "--filter bilinear"));
  state.key("T");  // the storage after compact in the storage registry
  EXPECT_TRUE(contains(state.render_command("o.png"), "--storage "));

  state.key("C");  // dsm's cluster count doubles: 1 -> 2 maps per light face
  EXPECT_TRUE(contains(state.render_command("o.png"), "--param clusters=2"))
      << state.render_command("o.png");
  EXPECT_TRUE(contains(state.render_command("o.png"), "--shadows dsm"));

  state.key("V");  // dsm rejects a voxelizer: the registry's error, the old method stays
  EXPECT_TRUE(contains(state.message(), "voxelizer")) << state.message();
  EXPECT_FALSE(contains(state.render_command("o.png"), "--voxelizer"));

  // The next method in the registry takes none of dsm's settings: they are dropped, noted.
  const std::vector<std::string> names = shadow_registry().names();
  const auto dsm = std::find(names.begin(), names.end(), "dsm");
  ASSERT_NE(dsm, names.end());
  const std::string next = dsm + 1 == names.end() ? names.front() : *(dsm + 1);
  state.key("M");
  EXPECT_TRUE(contains(state.render_command("o.png"), "--shadows " + next + " "));
  EXPECT_FALSE(contains(state.render_command("o.png"), "--eps"));
  EXPECT_TRUE(contains(state.message(), "dropped")) << state.message();
  EXPECT_TRUE(state.update());

  // On to the first method with no clusters parameter: there C is a message.
  const auto method_of = [](const ViewerState& v) {
    const std::string cmd = v.render_command("o.png");
    const size_t at = cmd.find("--shadows ") + 10;
    return cmd.substr(at, cmd.find(' ', at) - at);
  };
  for (size_t i = 0; i < names.size() &&
                     shadow_registry().create(method_of(state), {})->params().contains("clusters");
       ++i)
    state.key("M");
  state.key("C");
  EXPECT_TRUE(contains(state.message(), "no clusters parameter")) << state.message();
}

#if !DEEPVOX_WITH_CUDA
TEST(ViewerState, UnavailableBackendIsAMessage) {
  ViewerState state(small_dsm_setup());
  state.key("B");
  EXPECT_FALSE(state.message().empty());
  EXPECT_TRUE(contains(state.render_command("o.png"), "--backend cpu"));
}
#endif

TEST(ViewerState, HeatMapIsTheDsmLayers) {
  ViewerState state(small_dsm_setup());
  EXPECT_EQ(state.heatmap(), nullptr);
  state.key("H");
  state.update();
  ASSERT_NE(state.heatmap(), nullptr);
  EXPECT_GE(state.heatmap()->width, 64);
  state.key("M");  // the next method has no layers: no heat map, a message
  state.update();
  EXPECT_EQ(state.heatmap(), nullptr);
  EXPECT_TRUE(contains(state.message(), "only the dsm method")) << state.message();
  state.key("H");
  EXPECT_EQ(state.heatmap(), nullptr);
}

}  // namespace
}  // namespace dv::viewer
