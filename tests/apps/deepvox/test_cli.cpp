// The deepvox executable end to end: subcommands and their help, probe output against the
// in-process oracle, render outputs; clear errors for bad input are in test_cli_errors.cpp.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/oracle/transmittance.h"
#include "render/io/deep_exr.h"
#include "render/io/layer_heatmap.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/dsm_storage.h"
#include "tests/apps/deepvox/cli_fixture.h"
#include "tests/apps/deepvox/cli_run.h"
#include "tests/render/load/gltf_builder.h"

#if DEEPVOX_FULL_BINARY
#include <OpenImageIO/imageio.h>
#include "experiments/source_paths.h"
#endif

namespace dv {
namespace {

namespace fs = std::filesystem;

TEST_F(Cli, HelpAndList) {
  for (const char* sub : {"probe", "render", "info", "list", "dsm"}) {
    const CommandResult r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.output.find(sub), std::string::npos);
  }
  const CommandResult list = run("list");
  EXPECT_EQ(list.exit_code, 0);
  for (const char* name : {"reference", "none", "transmittance-slicemap", "storage", "voxelizer",
                           "icosphere", "shepp_logan", "cpu"})
    EXPECT_NE(list.output.find(name), std::string::npos) << name;
  EXPECT_NE(run("").exit_code, 0);
}

// docs/strategies.md is the output of `deepvox list --markdown`: the parameter tables the
// strategies register with, so the documentation cannot drift from the code.
TEST_F(Cli, StrategyDocsAreTheRegisteredTables) {
  const CommandResult r = run("list --markdown");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(test::source_dir() + "/docs/strategies.md");
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), r.output)
      << "regenerate: build/bin/deepvox list --markdown > docs/strategies.md";
  for (const char* row : {"| `eps` | 0.02 | >= 0 |", "| `storage.KEY` |", "| `slices` | 64 |",
                          "| `small` | 256 | an integer [0, 1048576] |"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row;
  const CommandResult text = run("list");
  EXPECT_NE(text.output.find("res=1024"), std::string::npos) << text.output;
}

// `deepvox list --json`, what the plots read: every registered strategy once, each with its
// plot family and colour; dsm is plotted as its storage.
TEST_F(Cli, ListJsonHasEveryStrategyWithFamilyAndColour) {
  const CommandResult r = run("list --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json list = nlohmann::json::parse(r.output).at("strategies");
  std::set<std::pair<std::string, std::string>> listed;
  for (const nlohmann::json& e : list) {
    const std::pair<std::string, std::string> key{e.at("registry"), e.at("name")};
    EXPECT_TRUE(listed.insert(key).second) << e.dump();
    EXPECT_FALSE(e.at("family").get<std::string>().empty()) << e.dump();
    EXPECT_FALSE(e.at("colour").get<std::string>().empty()) << e.dump();
    if (e.at("name").get<std::string>() == "dsm") EXPECT_EQ(e.at("member_param"), "storage");
  }
  for (const std::string& name : storage_registry().names())
    EXPECT_EQ(listed.count({"storage", name}), 1u) << name;
  for (const std::string& name : shadow_registry().names())
    EXPECT_EQ(listed.count({"shadow method", name}), 1u) << name;
  EXPECT_NE(run("list --json --markdown").exit_code, 0);
}

// docs/cli.md is the output of `deepvox help --markdown`: every command's own --help, so the
// reference cannot drift from the options the commands take. The file is the full binary's
// (with `view`); a binary without the viewer cannot reproduce it.
TEST_F(Cli, CliReferenceIsTheCommandsHelp) {
  if (run("view --help").exit_code != 0)
    GTEST_SKIP() << "this deepvox has no viewer (built without GLFW or OpenGL): docs/cli.md is "
                    "the full binary's help";
  const CommandResult r = run("help --markdown");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(test::source_dir() + "/docs/cli.md");
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), r.output)
      << "regenerate: build/bin/deepvox help --markdown > docs/cli.md";
  for (const char* heading :
       {"## deepvox render", "## deepvox suite", "## deepvox view", "--backend"})
    EXPECT_NE(r.output.find(heading), std::string::npos) << heading;
  EXPECT_EQ(r.output.find("## deepvox help"), std::string::npos);
}

// The CLI's shortcuts pass through the same table checks as --param: exit 2 naming the key.
TEST_F(Cli, ShortcutsMeetTheParameterTable) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string out = " --backend cpu --shadows dsm --out " + path("x.png");
  for (const auto& [args, key] : std::vector<std::pair<std::string, std::string>>{
           {" --eps -1", "eps"},
           {" --filter cubic", "filter"},
           {" --dsm-res 0", "res"},
           {" --param subrays=3", "subrays"},
           {" --param storage.layers=0 --storage texture3d", "layers"}}) {
    const CommandResult r = run("render " + scene + out + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << args << ": " << r.output;
  }
}

TEST_F(Cli, ProbeMatchesTheOracle) {
  const std::string scene = write("scene.json", kSmallScene);
  write("points.csv", "x,y,z\n0,0,0\n0.1,0.6,0.05\n1.5,0,1.5\n0,-1,0\n");
  const CommandResult r = run("probe " + scene + " --points " + path("points.csv") + " --out " +
                              path("t.csv") + " --backend cpu --shadows reference");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(path("t.csv"));
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "x,y,z,light0,light0_r,light0_g,light0_b");
  const Scene s = load_scene(scene);
  const SceneData data(s, Memory::host);
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    double x, y, z, t, r, g, b;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &x, &y, &z, &t, &r, &g, &b),
              7)
        << line;
    const OracleResult expected =
        exact_transmittance(data.view(), data.view().lights[0], {x, y, z});
    EXPECT_DOUBLE_EQ(t, expected.transmittance);
    EXPECT_DOUBLE_EQ(r, expected.rgb.x);
    EXPECT_DOUBLE_EQ(g, expected.rgb.y);
    EXPECT_DOUBLE_EQ(b, expected.rgb.z);
    ++rows;
  }
  EXPECT_EQ(rows, 4);
  // The point inside the glass cube sees its top face and part of its medium.
  const double inside =
      exact_transmittance(data.view(), data.view().lights[0], {0.1, 0.6, 0.05}).transmittance;
  EXPECT_GT(inside, 0.0);
  EXPECT_LT(inside, 0.6);
}

// Probe's colour columns: under the red glass stand-in the light is red, beside the luminance.
TEST_F(Cli, ProbeWritesColourColumns) {
  write("points.csv", "0,0,0\n");
  const CommandResult r =
      run("probe " + test::source_dir() + "/experiments/scenes/glass-red-slab.json --points " +
          path("points.csv") + " --out " + path("t.csv") + " --backend cpu --shadows reference");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(path("t.csv"));
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  double x, y, z, t, red, green, blue;
  ASSERT_EQ(
      std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &x, &y, &z, &t, &red, &green, &blue),
      7)
      << line;
  EXPECT_GT(red, 10.0 * green);
  EXPECT_NEAR(blue, green, 1e-12);
  EXPECT_NEAR(t, 0.2126 * red + 0.7152 * green + 0.0722 * blue, 1e-12);
}

TEST_F(Cli, RenderWritesImagesAndStats) {
  const std::string scene = write("scene.json", kSmallScene);
  const CommandResult r =
      run("render " + scene + " --backend cpu --out " + path("img.png") + " --stats " +
          path("s.json") + " --frames 2 --orbit 30 --dsm-res 128");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("img_0000.png")));
  EXPECT_TRUE(fs::exists(path("img_0001.png")));
  std::ifstream in(path("s.json"));
  const nlohmann::json stats = nlohmann::json::parse(in);
  ASSERT_EQ(stats["frames"].size(), 2u);
  EXPECT_GT(stats["frames"][0]["hits"].get<long long>(), 0);
  EXPECT_EQ(stats["frames"][0]["overflow_pixels"].get<long long>(), 0);
  EXPECT_EQ(stats["meta"]["backend"], "cpu");
  EXPECT_EQ(stats["shadows"]["name"], "auto");  // the default: the effect planner
  EXPECT_EQ(stats["frames"][1]["plan"]["lights"][0]["map"], "reused");
  const CommandResult info = run("info " + scene + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_EQ(nlohmann::json::parse(info.output)["triangles"].get<int>(), 24);
}

TEST_F(Cli, AutoShadowsAreTheDefaultAndExplainTheirPlan) {
  const std::string scene = write("scene.json", kSmallScene);
  const CommandResult planned =
      run("render " + scene + " --backend cpu --dsm-res 64 --out " + path("a.png") + " --explain");
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  EXPECT_NE(planned.output.find("frame 0: shadow plan\ncamera rays: no volume in the scene, no "
                                "volume sampling\nlight 0 (omni): dsm, it reaches 1 "
                                "constant medium but no volume"),
            std::string::npos)
      << planned.output;
  EXPECT_NE(planned.output.find("map built (no map yet)"), std::string::npos) << planned.output;
  EXPECT_NE(planned.output.find("effects in the scene and what auto shadows do with them:\n"
                                "  1 translucent caster (0 < alpha < 1): kept as dsm keeps it: "
                                "the planner runs dsm for every light that reaches it\n"
                                "  1 constant medium: kept as dsm keeps it: the planner runs dsm "
                                "for every light that reaches it\n"),
            std::string::npos)
      << planned.output;
  write("points.csv", "x,y,z\n0,0,0\n");
  const CommandResult forced =
      run("probe " + scene + " --points " + path("points.csv") + " --out " + path("t.csv") +
          " --shadows dsm --dsm-res 64 --explain");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_NE(forced.output.find("shadow method dsm was named, so it runs for every light"),
            std::string::npos)
      << forced.output;
  const CommandResult mapped = run("probe " + scene + " --points " + path("points.csv") +
                                   " --out " + path("m.csv") + " --shadows shadowmap --explain");
  ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
  EXPECT_NE(mapped.output.find(
                "effects in the scene and what shadowmap shadows do with them:\n"
                "  1 translucent caster (0 < alpha < 1): thresholded: one depth layer, so alpha "
                ">= 0.5 casts a full shadow and alpha < 0.5 none\n"
                "  1 constant medium: thresholded at its boundary: a full shadow where the "
                "medium's opacity across the object's thinnest extent d, 1 - exp(-sigma d), or "
                "its surface alpha reaches 0.5, else none (inside glass: the glass layer's "
                "Fresnel alone)\n"),
            std::string::npos)
      << mapped.output;
}

// --explain on the glTF stand-ins: alpha-textured casters are one row, cut per
// texel; coloured glass keeps its colour in the method that runs.
TEST_F(Cli, ExplainNamesAlphaTexturesAndColouredGlass) {
  write("points.csv", "x,y,z\n0,0,0\n");
  const CommandResult textured =
      run("probe " + test::source_dir() + "/tests/data/textured/alpha_mask_quad.gltf --points " +
          path("points.csv") + " --out " + path("a.csv") + " --shadows shadowmap --explain");
  ASSERT_EQ(textured.exit_code, 0) << textured.output;
  EXPECT_NE(textured.output.find(
                "effects in the scene and what shadowmap shadows do with them:\n"
                "  2 alpha-textured casters (MASK or BLEND): MASK cut per shadow-map texel; BLEND "
                "thresholded per texel: a full shadow where the texel's alpha times the factor's "
                "reaches 0.5, none below\n"),
            std::string::npos)
      << textured.output;
  const CommandResult glass =
      run("probe " + test::source_dir() + "/experiments/assets/gltf/red-glass-slab.gltf --points " +
          path("points.csv") + " --out " + path("g.csv") + " --shadows dsm --dsm-res 64 --explain");
  ASSERT_EQ(glass.exit_code, 0) << glass.output;
  EXPECT_NE(glass.output.find(
                "effects in the scene and what dsm shadows do with them:\n"
                "  1 transmissive (glass) caster: kept: each crossing's opacity, 1 - the "
                "luminance of the crossing rule (Fresnel at the texel ray's angle), in visibility "
                "functions compressed to within eps; its colour by the colour side channel (no "
                "refraction, no caustics)\n"
                "  1 tinted medium or coloured glass: kept by the colour side channel: exact for "
                "one tint per texel at every depth; where differently tinted casters share a "
                "texel, the far end's mix holds at every depth\n"),
            std::string::npos)
      << glass.output;
}

// kSmallScene with a floor whose edges lie outside the view: the thin front face of a small
// floor faces away from the light, and a map's receiver bias lights it (|T' - T| = 1 at the
// few percent of camera-visible points on it, a known limit of map methods on surface probes).
const std::string kAdviseScene = R"({
  "camera": {"position": [0, 1, 4], "target": [0, 0.3, 0], "width": 40, "height": 30},
  "lights": [{"type": "omni", "position": [0.5, 3, 0.5], "intensity": 9}],
  "objects": [
    {"mesh": {"generator": "box", "min": [-6, -0.1, -6], "max": [6, 0, 6]}},
    {"name": "glass", "mesh": {"generator": "box", "size": 0.6}, "transform": {"translate": [0, 0.6, 0]},
     "material": {"alpha": 0.4}, "interior": {"type": "constant", "sigma": 1.5}}
  ]
})";

// advise writes a shadow config of its pick that render and probe take with
// --config (and --param overrides it); a bad config or one beside --shadows is refused.
TEST_F(Cli, AdvisePickIsAConfigRenderAndProbeTake) {
  const std::string scene = write("scene.json", kAdviseScene);
  const CommandResult advised =
      run("advise " + scene + " --backend cpu --error 0.05 --width 32 --probes 100 --repeat 1 " +
          "--max-evaluations 6 --max-res 256 --out " + path("advice"));
  ASSERT_EQ(advised.exit_code, 0) << advised.output;
  EXPECT_NE(advised.output.find("Pareto front"), std::string::npos) << advised.output;
  EXPECT_NE(advised.output.find("param line: --shadows "), std::string::npos) << advised.output;
  EXPECT_TRUE(fs::exists(path("advice/front.svg")));
  std::ifstream in(path("advice/pick.json"));
  const nlohmann::json pick = nlohmann::json::parse(in);
  EXPECT_LE(pick["advice"]["verified"]["error_p95"].get<double>(), 0.05);
  const CommandResult rendered =
      run("render " + scene + " --backend cpu --config " + path("advice/pick.json") + " --out " +
          path("a.png") + " --stats " + path("s.json"));
  ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
  std::ifstream stats_in(path("s.json"));
  const nlohmann::json stats = nlohmann::json::parse(stats_in);
  EXPECT_EQ(stats["shadows"]["name"], pick["shadows"]["name"]);
  // The same values; a number as the method holds it (dsm keeps eps in single precision).
  for (const auto& [key, value] : pick["shadows"]["params"].items()) {
    if (key.find('.') != std::string::npos) continue;
    const nlohmann::json& used = stats["shadows"]["params"][key];
    if (value.is_number_float())
      EXPECT_EQ(float(used.get<double>()), float(value.get<double>())) << key;
    else
      EXPECT_EQ(used, value) << key;
  }
  write("points.csv", "x,y,z\n0,0.3,0\n");
  const CommandResult probed =
      run("probe " + scene + " --points " + path("points.csv") + " --out " + path("t.csv") +
          " --config " + path("advice/pick.json") + " --param res=64");
  EXPECT_EQ(probed.exit_code, 0) << probed.output;
  expect_error("render " + scene + " --config " + path("advice/pick.json") +
                   " --shadows dsm --out " + path("b.png"),
               {"--config", "--shadows"});
  const std::string bad = write("bad.json", R"({"format": "deepvox-shadow-config", "version": 9,
                                              "shadows": {"name": "dsm"}})");
  expect_error("render " + scene + " --config " + bad + " --out " + path("b.png"),
               {"bad.json", "version"});
}

// advise --time times config files alternately in one process (what advise's final timing
// does, and what scripts/advise_check.py compares a pick with the sweep's cheapest by).
TEST_F(Cli, AdviseTimeTimesConfigsInInterleavedRounds) {
  const std::string scene = write("scene.json", kAdviseScene);
  const std::string a = write("a.json", R"({"format": "deepvox-shadow-config", "version": 1,
                                          "shadows": {"name": "dsm", "params": {"res": 64}}})");
  const std::string b = write("b.json", R"({"format": "deepvox-shadow-config", "version": 1,
                                          "shadows": {"name": "shadowmap", "params": {"res": 64}}})");
  const CommandResult timed = run("advise " + scene + " --backend cpu --width 32 --repeat 1 " +
                                  "--rounds 3 --time " + a + " " + b + " --out " + path("t"));
  ASSERT_EQ(timed.exit_code, 0) << timed.output;
  EXPECT_NE(timed.output.find("over 3 rounds: --shadows dsm --param res=64"), std::string::npos)
      << timed.output;
  std::ifstream in(path("t/timing.json"));
  const nlohmann::json timing = nlohmann::json::parse(in);
  ASSERT_EQ(timing["configs"].size(), 2u);
  EXPECT_EQ(timing["rounds"], 3);
  for (const nlohmann::json& c : timing["configs"]) {
    ASSERT_EQ(c["times_ms"].size(), 3u) << c.dump();
    for (const nlohmann::json& ms : c["times_ms"]) EXPECT_GT(ms.get<double>(), 0.0);
    EXPECT_LE(c["min_ms"].get<double>(), c["median_ms"].get<double>());
    EXPECT_LE(c["median_ms"].get<double>(), c["max_ms"].get<double>());
  }
  expect_error(
      "advise " + scene + " --backend cpu --time " + path("missing.json") + " --out " + path("t2"),
      {"missing.json"});
}

// --error-budget chooses auto's parameters for the scene and --explain says how and why.
TEST_F(Cli, ErrorBudgetChoosesAutosParametersAndExplains) {
  const std::string scene = write("scene.json", kAdviseScene);
  const CommandResult r = run("render " + scene + " --backend cpu --error-budget 0.05 --explain " +
                              "--width 32 --height 24 --out " + path("a.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("error budget 0.05"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("light 0 (media"), std::string::npos) << r.output;
  expect_error("render " + scene + " --error-budget 0.05 --shadows dsm --out " + path("b.png"),
               {"--error-budget", "auto"});
}

TEST_F(Cli, RenderViewMovesTheCameraAndRejectsBadMoves) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string common =
      "render " + scene + " --backend cpu --width 32 --height 24 --dsm-res 128";
  ASSERT_EQ(run(common + " --out " + path("plain.png")).exit_code, 0);
  ASSERT_EQ(run(common + " --out " + path("still.png") + " --view 0,0,1,0,0").exit_code, 0);
  ASSERT_EQ(run(common + " --out " + path("moved.png") + " --view 20,-5,0.8,0.1,0").exit_code, 0);
  const auto bytes = [&](const std::string& name) {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_TRUE(bytes("plain.png") == bytes("still.png"));
  EXPECT_FALSE(bytes("plain.png") == bytes("moved.png"));
  const CommandResult zero = run(common + " --out " + path("z.png") + " --view 0,0,0,0,0");
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("--view: the dolly factor must be positive"), std::string::npos)
      << zero.output;
  EXPECT_EQ(run(common + " --out " + path("z.png") + " --view 1,2").exit_code, 2);
}

// Width and height from a PNG file's IHDR chunk.
std::pair<int, int> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  const auto be = [&](int i) {
    return (h[i] << 24) | (h[i + 1] << 16) | (h[i + 2] << 8) | h[i + 3];
  };
  return {be(16), be(20)};
}

TEST_F(Cli, DsmExportsDeepExrHeatmapAndStats) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string tail = " --dsm-res 16 --eps 0.05 --backend cpu --heatmap " +
                           path("layers.png") + " --stats " + path("s.json");
  const CommandResult r =
      run("dsm " + scene + tail + (DEEPVOX_FULL_BINARY ? " --out " + path("maps.exr") : ""));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto [width, height] = png_size(path("layers.png"));
  EXPECT_LT(width, 6 * 16 + 5);  // a 3 x 2 grid, narrower than the six faces in a row
  EXPECT_GT(height, 2 * 16 + 4);
  std::ifstream in(path("s.json"));
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["faces"].get<int>(), 6);
  EXPECT_GT(stats["figures"]["nodes"].get<long long>(), 0);
  EXPECT_GT(stats["passes"].size(), 1u);
  EXPECT_EQ(stats["meta"]["backend"], "cpu");
  EXPECT_EQ(stats["settings"]["storage"], "compact");
#if DEEPVOX_FULL_BINARY
  const DeepMapFile maps = read_deep_exr(path("maps.exr"));
  ASSERT_EQ(maps.faces.size(), 6u);
  size_t nodes = 0;
  for (const DeepMapFace& f : maps.faces) nodes += f.nodes.size();
  EXPECT_EQ(nodes, stats["figures"]["nodes"].get<size_t>());
  EXPECT_EQ(maps.commit, stats["meta"]["git_sha"]);
#endif
  expect_error("dsm " + scene + " --out " + path("maps.png"), {"maps.png", ".exr"});
  expect_error("dsm " + scene, {"--out", "--heatmap"});
  expect_error("dsm " + path("none.json") + " --heatmap " + path("h.png"), {"none.json"});
}

TEST_F(Cli, MeshFileIsASceneOfOneObjectStagedOnAGround) {
  const std::string mesh =
      test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  const CommandResult r = run("info " + mesh + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  ASSERT_EQ(j["objects"].size(), 2u);  // the model and the staged ground
  EXPECT_EQ(j["objects"][1]["name"], "ground");
  EXPECT_EQ(j["triangles"].get<int>(), 3674 + 2);
  EXPECT_EQ(j["lights"].size(), 2u);  // the default key and fill lights
}

TEST_F(Cli, InfoListsLightColoursAndUnitsAndWarnsAboutFullyTransmissiveGlass) {
  test::GltfBuilder b;
  b.use_extension("KHR_lights_punctual");
  b.use_extension("KHR_materials_transmission");
  const int glass = b.add_material(
      {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}});
  b.add_node({{"name", "vase"}, {"mesh", test::add_box_mesh(b, {{"material", glass}})}});
  const int lamp =
      b.add_light({{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 68.3}});
  b.add_node(
      {{"translation", {0, 3, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", lamp}}}}}});
  const std::string gltf = b.write_gltf(path("glass.gltf"));
  const CommandResult text = run("info " + gltf);
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* needle : {"color [1.0,0.5,0.25]", "intensity 0.1 W/sr (from 68.3 cd)", "warning",
                             "'vase' is fully transmissive"})
    EXPECT_NE(text.output.find(needle), std::string::npos) << needle << " in " << text.output;
  const CommandResult js = run("info " + gltf + " --json");
  ASSERT_EQ(js.exit_code, 0) << js.output;
  const nlohmann::json j = nlohmann::json::parse(js.output);
  ASSERT_EQ(j["lights"].size(), 1u);
  EXPECT_EQ(j["lights"][0]["unit"], "W/sr");
  EXPECT_EQ(j["lights"][0]["source"]["unit"], "cd");
  EXPECT_DOUBLE_EQ(j["lights"][0]["source"]["intensity"].get<double>(), 68.3);
  EXPECT_DOUBLE_EQ(j["lights"][0]["color"][2].get<double>(), 0.25);
  ASSERT_EQ(j["warnings"].size(), 1u);
  const CommandResult own = run("info " + write("scene.json", kSmallScene) + " --json");
  EXPECT_TRUE(nlohmann::json::parse(own.output)["warnings"].empty());
}

std::string file_bytes(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

#if DEEPVOX_FULL_BINARY
// The float pixels of an EXR file (its header holds a capture date, so files never match).
std::vector<float> exr_pixels(const std::string& file) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}
#endif

TEST_F(Cli, ExposureAndToneCurveChangePngsOnlyAndGroundAddsAPlane) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string base =
      "render " + scene + " --backend cpu --width 32 --height 24 --dsm-res 128 --out ";
  const std::string look = " --exposure 1.5 --tonemap aces";
  ASSERT_EQ(run(base + path("plain.png")).exit_code, 0);
  const CommandResult r = run(base + path("look.png") + look + " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(file_bytes(path("plain.png")), file_bytes(path("look.png")));
  std::ifstream in(path("s.json"));
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["display"]["tonemap"], "aces");
  EXPECT_DOUBLE_EQ(stats["display"]["exposure_ev"].get<double>(), 1.5);
#if DEEPVOX_FULL_BINARY
  ASSERT_EQ(run(base + path("plain.exr")).exit_code, 0);
  ASSERT_EQ(run(base + path("look.exr") + look).exit_code, 0);
  EXPECT_EQ(exr_pixels(path("plain.exr")), exr_pixels(path("look.exr")));  // linear, untouched
  EXPECT_FALSE(exr_pixels(path("plain.exr")).empty());
#endif
  const std::string mesh =
      test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  const CommandResult g =
      run("render " + mesh + " --backend cpu --width 32 --height 24 --ground --out " +
          path("g.png") + " --stats " + path("g.json"));
  ASSERT_EQ(g.exit_code, 0) << g.output;
  std::ifstream gin(path("g.json"));
  EXPECT_EQ(nlohmann::json::parse(gin)["triangles"].get<int>(), 3674 + 2);
  // A staged mesh gets the ground without --ground; --no-ground drops it.
  const std::string small = " --backend cpu --width 32 --height 24 --out ";
  ASSERT_EQ(run("render " + mesh + small + path("d.png") + " --stats " + path("d.json")).exit_code,
            0);
  std::ifstream din(path("d.json"));
  EXPECT_EQ(nlohmann::json::parse(din)["triangles"].get<int>(), 3674 + 2);
  ASSERT_EQ(run("render " + mesh + small + path("n.png") + " --no-ground --stats " + path("n.json"))
                .exit_code,
            0);
  std::ifstream nin(path("n.json"));
  EXPECT_EQ(nlohmann::json::parse(nin)["triangles"].get<int>(), 3674);
  EXPECT_EQ(run("render " + mesh + small + path("x.png") + " --ground --no-ground").exit_code, 2);
  // The default tone curve is aces (no clipping of a white model under the staged key).
  ASSERT_EQ(run("render " + mesh + small + path("a.png") + " --tonemap aces").exit_code, 0);
  EXPECT_EQ(file_bytes(path("d.png")), file_bytes(path("a.png")));
  ASSERT_EQ(run("render " + mesh + small + path("c.png") + " --tonemap none").exit_code, 0);
  EXPECT_NE(file_bytes(path("d.png")), file_bytes(path("c.png")));
  const CommandResult bad = run(base + path("x.png") + " --tonemap filmic");
  EXPECT_NE(bad.exit_code, 0) << bad.output;  // CLI11 rejects it, naming the value
  EXPECT_LT(bad.exit_code, 128) << bad.output;
  EXPECT_NE(bad.output.find("filmic"), std::string::npos) << bad.output;
}

// Five omni lights (30 faces, each 16 x 16): a labelled grid instead of one row 509 pixels wide.
TEST_F(Cli, HeatmapLaysManyFacesInAGrid) {
  std::string scene = kSmallScene;
  const std::string light = R"({"type": "omni", "position": [0.5, 3, 0.5], "intensity": 9})";
  scene.replace(scene.find(light), light.size(),
                light + "," + light + "," + light + "," + light + "," + light);
  const CommandResult r = run("dsm " + write("five.json", scene) +
                              " --dsm-res 16 --backend cpu --heatmap " + path("h.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto [width, height] = png_size(path("h.png"));
  EXPECT_LE(width, 7 * 32);   // 6 columns of at most 32 pixels
  EXPECT_GE(height, 5 * 16);  // 5 rows
}

// The grid itself: 30 faces in 6 columns and 5 rows, each face's label drawn in white in the
// band above it (absent without labels).
TEST(Heatmap, GridOfLabelledFaces) {
  const int faces = 30, res = 16;
  const std::vector<int32_t> layers(size_t(faces) * res * res, 1);
  std::vector<std::string> labels;
  for (int f = 0; f < faces; ++f) labels.push_back("L" + std::to_string(f / 6) + " +X");
  const Image plain = layer_heatmap(layers, faces, res);
  EXPECT_EQ(plain.width, 6 * res + 5);
  EXPECT_GE(plain.height, 5 * res);
  const Image labelled = layer_heatmap(layers, faces, res, labels);
  const int cell = (labelled.width - 5) / 6;
  ASSERT_EQ(labelled.width, 6 * cell + 5);
  EXPECT_GT(labelled.height, plain.height);
  const int row = (labelled.height - (plain.height - 5 * (res + 1))) / 5;
  for (int f = 0; f < faces; ++f) {
    int white = 0;
    for (int y = (f / 6) * row; y < (f / 6) * row + row - res - 1; ++y)
      for (int x = (f % 6) * (cell + 1); x < (f % 6) * (cell + 1) + cell; ++x)
        white += labelled.at(x, y) == dvec3(1.0);
    EXPECT_GT(white, 10) << "no label above face " << f;
  }
}

// --version names the version, the commit and the build.
TEST_F(Cli, VersionNamesCommitAndBuild) {
  const CommandResult r = run("--version");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* needle : {"deepvox 0.", "\ncommit ", "\nbuild ", "CUDA "})
    EXPECT_NE(r.output.find(needle), std::string::npos) << needle << " in " << r.output;
}

// `deepvox help COMMAND` is `deepvox COMMAND --help`; an unknown command exits 2 naming it.
TEST_F(Cli, HelpOfOneCommand) {
  const CommandResult help = run("help render");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_EQ(help.output, run("render --help").output);
  const CommandResult bad = run("help rendr");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("unknown command 'rendr'; did you mean 'render'?"), std::string::npos)
      << bad.output;
}

// render --help shows the defaults of the dsm shortcuts (the dsm's parameter table) and of the
// image size (the scene camera's).
TEST_F(Cli, RenderHelpShowsDefaults) {
  const std::string help = run("render --help").output;
  for (const char* needle : {"--storage TEXT=", "--dsm-res INT=", "--eps FLOAT=", "--filter TEXT=",
                             "16384]=camera", "--exposure FLOAT:FLOAT in [-64 - 64]=scene"})
    EXPECT_NE(help.find(needle), std::string::npos) << needle << " in " << help;
}

// voxelize reads only geometry: no staged lights, and no word about them.
TEST_F(Cli, VoxelizeSaysNothingAboutLights) {
  test::GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  const std::string gltf = b.write_gltf(path("box.gltf"));
  const CommandResult r =
      run("voxelize " + gltf + " --backend cpu --res 32x32x32 --out " + path("box.binvox"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("light"), std::string::npos) << r.output;
  const CommandResult info = run("info " + gltf);  // info still stages them, and says so
  EXPECT_NE(info.output.find("added the default key and fill lights"), std::string::npos)
      << info.output;
}

// info: glass shows its transmission, and one warning line covers every glass object.
TEST_F(Cli, InfoShowsTransmissionAndOneWarningForManyGlassObjects) {
  test::GltfBuilder b;
  b.use_extension("KHR_materials_transmission");
  const int glass = b.add_material(
      {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}});
  const int mesh = test::add_box_mesh(b, {{"material", glass}});
  for (int i = 0; i < 5; ++i)
    b.add_node({{"name", "pane" + std::to_string(i)},
                {"mesh", mesh},
                {"translation", {3.0 * i, 0.0, 0.0}}});
  const CommandResult r = run("info " + b.write_gltf(path("panes.gltf")));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("alpha 0  transmission 1  interior none"), std::string::npos) << r.output;
  size_t warnings = 0;
  for (size_t at = r.output.find("\nwarning "); at != std::string::npos;
       at = r.output.find("\nwarning ", at + 1))
    ++warnings;
  EXPECT_EQ(warnings, 1u) << r.output;
  EXPECT_NE(r.output.find("5 objects ('pane0', 'pane1', 'pane2' and 2 more) are fully "
                          "transmissive"),
            std::string::npos)
      << r.output;
}

// A missing base-colour image no longer refuses the model: info and render go on, warning.
TEST_F(Cli, MissingBaseColourImageWarnsAndRenders) {
  test::GltfBuilder b;
  const std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1};
  b.doc["images"] = nlohmann::json::array({{{"uri", "lost.png"}}});
  b.doc["textures"] = nlohmann::json::array({{{"source", 0}}});
  const int material =
      b.add_material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  b.add_node(
      {{"mesh",
        b.add_mesh({{"attributes",
                     {{"POSITION", b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0})},
                      {"TEXCOORD_0", b.add_accessor(b.add_view(uv.data(), 32), 5126, 4, "VEC2")}}},
                    {"indices", b.add_indices({0, 1, 2, 0, 2, 3})},
                    {"material", material}})}});
  const std::string gltf = b.write_gltf(path("lost.gltf"));
  const CommandResult info = run("info " + gltf);
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("lost.png: file not found"), std::string::npos) << info.output;
  const CommandResult r =
      run("render " + gltf + " --backend cpu --width 24 --height 18 --out " + path("l.png"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// A glTF lit by its own photometric lights renders at log2(683 / pi) EV unless --exposure says
// otherwise; a staged one at 0 EV.
TEST_F(Cli, PhotometricLightsSetTheDefaultExposure) {
  test::GltfBuilder b;
  b.use_extension("KHR_lights_punctual");
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  const int lamp = b.add_light({{"type", "point"}, {"intensity", 20.0}});
  b.add_node(
      {{"translation", {0, 3, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", lamp}}}}}});
  const std::string gltf = b.write_gltf(path("lamp.gltf"));
  const auto exposure = [&](const std::string& extra) {
    const CommandResult r = run("render " + gltf + " --backend cpu --width 24 --height 18 --out " +
                                path("x.png") + " --stats " + path("x.json") + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(path("x.json"));
    return nlohmann::json::parse(in)["display"]["exposure_ev"].get<double>();
  };
  EXPECT_NEAR(exposure(""), std::log2(683.0 / 3.14159265358979323846), 1e-12);
  EXPECT_EQ(exposure(" --exposure 0"), 0.0);
  test::GltfBuilder bare;
  bare.add_node({{"mesh", test::add_box_mesh(bare)}});
  const CommandResult r = run("render " + bare.write_gltf(path("bare.gltf")) +
                              " --backend cpu --width 24 --height 18 --out " + path("b.png") +
                              " --stats " + path("b.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(path("b.json"));
  EXPECT_EQ(nlohmann::json::parse(in)["display"]["exposure_ev"].get<double>(), 0.0);
}

}  // namespace
}  // namespace dv
