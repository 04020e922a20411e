// `deepvox view` end to end under Xvfb (Mesa llvmpipe, the CPU backend): a script orbits,
// switches dsm -> shadowmap -> reference, toggles the heat map, saves after each step (S) and
// takes screenshots; every screenshot must equal, byte for byte, the PNG `deepvox render`
// writes with the same settings (the saved command line, and one written out by hand), and the
// window's framebuffer without overlays must equal it too. Starts Xvfb itself through
// `xvfb-run -a` when there is no DISPLAY; skips only when xvfb-run is not installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "engine/raster/camera_rays.h"
#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"
#include "tests/apps/viewer/viewer_test_support.h"

namespace dv {
namespace {

namespace fs = std::filesystem;
using test::kDeepvox;
using test::read_file;
using Result = test::ShellResult;
using test::shell;

const std::string kScene = test::source_dir() + "/experiments/scenes/translucent-boxes.json";

class ViewerXvfb : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(test::binary_dir()) / "test_viewer_tmp" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const char* display = std::getenv("DISPLAY");
    if (display && *display) return;
    if (shell("command -v xvfb-run").exit_code != 0)
      GTEST_SKIP() << "no DISPLAY and xvfb-run is not installed (Debian package xvfb)";
    wrapper_ = "xvfb-run -a -s '-screen 0 320x240x24' ";
  }
  // `deepvox view` under the display (or Xvfb), in the test's directory.
  Result view(const std::string& args) {
    return shell("cd " + dir_.string() + " && LIBGL_ALWAYS_SOFTWARE=1 " + wrapper_ + kDeepvox +
                 " view " + args);
  }
  fs::path dir_;
  std::string wrapper_;
};

TEST_F(ViewerXvfb, ScriptedRunEqualsRender) {
  // Frame numbers: the view renders at most once a frame, after that frame's events.
  std::ofstream(dir_ / "keys.txt")
      << "0 screenshot dsm.png\n"
         "1 drag 40 -12\n"
         "1 key S\n"  // _000: dsm, orbited
         "1 screenshot dsm_orbit.png\n"
         "2 key H\n"  // heat map on: the render image is unchanged
         "2 screenshot dsm_heat.png\n"
         "3 key M\n3 key M\n3 key M\n"  // dsm -> none -> reference -> shadowmap
         "3 key S\n"                    // _001: shadowmap
         "3 screenshot shadowmap.png\n"
         "4 key M\n4 key M\n4 key M\n4 key M\n4 key M\n"  // -> t-slicemap, auto, dsm, none,
                                                          // reference
         "4 key S\n"                                      // _002: reference
         "4 screenshot reference.png\n"
         "5 key H\n5 key P\n";  // overlays off for the window shot
  const std::string size = " --width 96 --height 64";
  const Result r = view(kScene + " --backend cpu --shadows dsm --dsm-res 128" + size +
                        " --script keys.txt --screenshot last.png --screenshot-window window.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The registry's order decides what M reaches; the saved command names the method.
  EXPECT_NE(read_file(dir_ / "deepvox-view_001.txt").find("--shadows shadowmap "),
            std::string::npos);
  EXPECT_NE(read_file(dir_ / "deepvox-view_002.txt").find("--shadows reference "),
            std::string::npos);

  // Each saved command line, run as it is, reproduces its screenshot exactly.
  const std::pair<const char*, const char*> saved[] = {{"deepvox-view_000", "dsm_orbit.png"},
                                                       {"deepvox-view_001", "shadowmap.png"},
                                                       {"deepvox-view_002", "reference.png"}};
  for (const auto& [prefix, shot] : saved) {
    std::string command = read_file(dir_ / (std::string(prefix) + ".txt"));
    ASSERT_EQ(command.rfind("deepvox render ", 0), 0u) << command;
    command.replace(0, 7, kDeepvox);
    const std::string replay = (dir_ / (std::string(prefix) + "_replay.png")).string();
    command.replace(command.find(std::string(" --out ") + prefix + ".png"),
                    std::string(" --out ").size() + std::string(prefix).size() + 4,
                    " --out " + replay);
    command.pop_back();  // the newline
    const Result rendered = shell("cd " + dir_.string() + " && " + command);
    ASSERT_EQ(rendered.exit_code, 0) << command << "\n" << rendered.output;
    EXPECT_TRUE(read_file(replay) == read_file(dir_ / shot)) << prefix << " vs " << shot;
    EXPECT_TRUE(read_file(dir_ / (std::string(prefix) + ".png")) == read_file(dir_ / shot));
  }

  // Written out by hand, independently of the viewer's own command lines.
  const std::string render = kDeepvox + " render " + kScene + " --backend cpu" + size;
  const std::pair<std::string, std::string> by_hand[] = {
      {" --shadows dsm --dsm-res 128", "dsm.png"},
      {" --shadows dsm --dsm-res 128 --view -10,-3,1,0,0", "dsm_orbit.png"},
      {" --shadows dsm --dsm-res 128 --view -10,-3,1,0,0", "dsm_heat.png"},
      {" --shadows shadowmap --view -10,-3,1,0,0", "shadowmap.png"},
      {" --shadows reference --view -10,-3,1,0,0", "reference.png"},
      {" --shadows reference --view -10,-3,1,0,0", "last.png"},
      {" --shadows reference --view -10,-3,1,0,0", "window.png"}};
  for (const auto& [args, shot] : by_hand) {
    const std::string out = (dir_ / ("render_" + shot)).string();
    const Result rendered = shell(render + args + " --out " + out);
    ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
    EXPECT_TRUE(read_file(out) == read_file(dir_ / shot)) << shot << " differs from render" << args;
  }
  EXPECT_FALSE(read_file(dir_ / "dsm.png") == read_file(dir_ / "dsm_orbit.png"));  // it orbited
  EXPECT_FALSE(read_file(dir_ / "dsm_orbit.png") == read_file(dir_ / "shadowmap.png"));
}

TEST_F(ViewerXvfb, BadScriptExitsTwoNamingFileAndLine) {
  std::ofstream(dir_ / "bad.txt") << "0 key M\n1 key NOPE\n";
  const Result r = view(kScene + " --backend cpu --width 32 --height 24 --script bad.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.txt:2: unknown key 'NOPE'"), std::string::npos) << r.output;
}

TEST_F(ViewerXvfb, FramesAndScreenshotWithoutScript) {
  const Result r = view(kScene + " --backend cpu --shadows shadowmap --width 40 --height 30" +
                        " --frames 2 --screenshot s.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string out = (dir_ / "r.png").string();
  ASSERT_EQ(shell(kDeepvox + " render " + kScene +
                  " --backend cpu --shadows shadowmap --width 40 --height 30 --out " + out)
                .exit_code,
            0);
  EXPECT_TRUE(read_file(out) == read_file(dir_ / "s.png"));
}

// The error view (E) and the voxel grid overlay (G) change the window, never the rendered image;
// the error view's maximum and mean (in the stats S saves) equal `deepvox probe`'s.
TEST_F(ViewerXvfb, OverlaysChangeTheWindowAndErrorViewEqualsProbe) {
  const std::string size = " --width 96 --height 64";
  const std::string dsm = " --shadows dsm --dsm-res 64";
  const std::string slicemap = " --shadows transmittance-slicemap --param res=64";
  const auto run = [&](const std::string& method, const std::string& keys,
                       const std::string& name) {
    std::ofstream(dir_ / (name + ".txt")) << keys;
    const Result r = view(kScene + " --backend cpu" + method + size + " --script " + name +
                          ".txt --save-prefix " + name + " --screenshot " + name +
                          "_image.png --screenshot-window " + name + "_window.png");
    EXPECT_EQ(r.exit_code, 0) << r.output;
  };
  run(dsm, "0 key P\n1 key S\n", "dsm_plain");
  run(dsm, "0 key P\n0 key E\n1 key S\n", "dsm_error");
  run(slicemap, "0 key P\n1 key S\n", "slicemap_plain");
  run(slicemap, "0 key P\n0 key G\n1 key S\n", "slicemap_grid");
  EXPECT_FALSE(read_file(dir_ / "dsm_error_window.png") ==
               read_file(dir_ / "dsm_plain_window.png"));
  EXPECT_FALSE(read_file(dir_ / "slicemap_grid_window.png") ==
               read_file(dir_ / "slicemap_plain_window.png"));
  // Without overlays the window is the image; the overlays leave the image alone.
  EXPECT_TRUE(read_file(dir_ / "dsm_plain_window.png") == read_file(dir_ / "dsm_plain_image.png"));
  EXPECT_TRUE(read_file(dir_ / "dsm_error_image.png") == read_file(dir_ / "dsm_plain_image.png"));
  EXPECT_TRUE(read_file(dir_ / "slicemap_grid_image.png") ==
              read_file(dir_ / "slicemap_plain_image.png"));

  const nlohmann::json stats = nlohmann::json::parse(read_file(dir_ / "dsm_error_000.json"));
  ASSERT_TRUE(stats.contains("error_view")) << stats.dump();
  const double max = stats["error_view"]["max"], mean = stats["error_view"]["mean"];
  EXPECT_GT(max, 0.0);
  Scene scene = load_scene(kScene);
  scene.camera.width = 96;
  scene.camera.height = 64;
  const test::IndependentError ref =
      test::independent_error(kScene, scene, scene.camera, dsm, dir_);
  ASSERT_TRUE(ref.failure.empty()) << ref.failure;
  EXPECT_NEAR(max, ref.max, 1e-9);
  EXPECT_NEAR(mean, ref.mean, 1e-9);
  EXPECT_EQ(stats["error_view"]["pixels"].get<int64_t>(), ref.pixels);
  std::printf("error view under Xvfb, dsm res 64, 96x64: max %.6g mean %.6g (probe: %.6g %.6g)\n",
              max, mean, ref.max, ref.mean);

  const nlohmann::json grid = nlohmann::json::parse(read_file(dir_ / "slicemap_grid_000.json"));
  EXPECT_GT(grid["shadows"]["stats"]["set_voxels"].get<int64_t>(), 0);
}

}  // namespace
}  // namespace dv
