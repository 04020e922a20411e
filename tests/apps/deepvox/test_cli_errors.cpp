// The deepvox executable's errors: bad input of every kind gives a clean failure naming the
// file and the problem (non-zero exit, no crash), command-line mistakes exit 2 naming the word,
// and every output is checked before any input is read or any work is done.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "tests/apps/deepvox/cli_fixture.h"
#include "tests/apps/deepvox/cli_run.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

TEST_F(Cli, BadInputGivesClearErrors) {
  const std::string probe_tail =
      " --points " + write("p.csv", "0,0,0\n") + " --out " + path("o.csv");
  expect_error("info " + path("missing.json"), {"missing.json", "not found"});
  expect_error("info " + write("bad.json", "{\"objects\": [}"), {"bad.json", "malformed JSON"});
  expect_error("info " + write("key.json", R"({"lights": [{"type": "omni", "position": [0,1,0]}],
      "objects": [{"mesh": {"generator": "box"}, "colour": [1,0,0]}]})"),
               {"key.json", "colour"});
  expect_error("info " + write("gen.json", R"({"lights": [{"type": "omni", "position": [0,1,0]}],
      "objects": [{"mesh": {"generator": "dodecahedron"}}]})"),
               {"gen.json", "dodecahedron", "icosphere"});
  expect_error("info " + write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"), {"nan.obj"});
  expect_error("info " + write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), {"range.obj"});
  expect_error("info " + write("zero.json", R"({"lights": [{"type": "omni", "position": [0,1,0]}],
      "volumes": {"v": {"generator": "block", "dims": [0, 4, 4]}},
      "objects": [{"mesh": {"generator": "box"}}]})"),
               {"zero.json", "zero-size"});
  expect_error("info " + write("open.json", R"({"lights": [{"type": "omni", "position": [0,1,0]}],
      "objects": [{"mesh": {"generator": "quad"}, "interior": {"type": "constant", "sigma": 1}}]})"),
               {"open.json", "not closed", "open edge"});
  expect_error("info " + write("light.json", R"({"lights": [{"type": "area", "position": [0,1,0]}],
      "objects": [{"mesh": {"generator": "box"}}]})"),
               {"light.json", "area", "spot"});
  const std::string scene = write("scene.json", kSmallScene);
  expect_error("probe " + scene + " --shadows magic" + probe_tail, {"magic", "reference"});
  expect_error("probe " + scene + " --points " + write("garbage.csv", "x,y,z\n1,2,3\n1,two,3\n") +
                   " --out " + path("o.csv"),
               {"garbage.csv:3"});
  expect_error("probe " + scene + probe_tail + " --backend opencl", {"opencl"});
  expect_error("render " + scene + " --out " + path("img.bmp") + " --backend cpu",
               {"img.bmp", ".png"});
  expect_error("info " + write("scene.txt", "hello"), {"scene.txt", ".json"});
}

// Expects exit code 2 and a message holding every fragment.
void expect_usage_error(const std::string& args, std::initializer_list<std::string> fragments) {
  const CommandResult r = run(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("deepvox: error: "), std::string::npos) << r.output;
  for (const std::string& f : fragments)
    EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
}

TEST_F(Cli, CommandLineMistakesExitTwoNamingTheWord) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string out = " --out " + path("img.png");
  expect_usage_error("renderr " + scene + out,
                     {"unknown subcommand 'renderr'", "did you mean 'render'?"});
  expect_usage_error("voxelise " + scene, {"'voxelise'", "did you mean 'voxelize'?"});
  expect_usage_error("render " + scene + out + " --shadow dsm",
                     {"unknown option '--shadow'", "did you mean '--shadows'?"});
  expect_usage_error("render " + scene + " --shadow dsm", {"'--shadow'", "'--shadows'"});
  expect_usage_error("dsm " + scene + " --heatmpa " + path("h.png"),
                     {"'--heatmpa'", "did you mean '--heatmap'?"});
  expect_usage_error("render " + scene + out + " --backend foo", {"foo", "cpu, cuda"});
  expect_usage_error("render " + scene + out + " --frames -1", {"--frames", "-1"});
  expect_usage_error("render " + scene + out + " --renderer rays", {"--renderer", "rays"});
  expect_usage_error("render " + scene, {"--out", "required"});
  expect_usage_error("probe " + scene + " --out " + path("t.csv"), {"--points", "required"});
  expect_usage_error("render " + scene + " " + scene + out, {"unexpected argument"});
  expect_usage_error("--verbose render " + scene + out, {"'--verbose'"});
  expect_usage_error("", {"subcommand", "render"});
  for (const char* help : {"--help", "render --help", "dsm -h"}) {
    const CommandResult r = run(help);
    EXPECT_EQ(r.exit_code, 0) << help << ": " << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << r.output;
  }
}

// Every output is checked before any input is read or any work is done: with a missing input
// and a bad output, the output is what fails; with one good and one bad output, nothing is
// written.
TEST_F(Cli, OutputsAreCheckedBeforeAnyWork) {
  const std::string scene = write("scene.json", kSmallScene);
  const std::string missing_dir = path("no_such_dir");
  const std::string missing_scene = path("missing.json");
  expect_usage_error("render " + scene + " --backend cpu --out " + path("img.png") + " --stats " +
                         missing_dir + "/s.json",
                     {missing_dir + "/s.json", "does not exist"});
  EXPECT_FALSE(fs::exists(path("img.png"))) << "the render ran before the stats path was checked";
  expect_usage_error("dsm " + scene + " --backend cpu --dsm-res 8 --heatmap " + path("h.png") +
                         " --stats " + missing_dir + "/s.json",
                     {missing_dir + "/s.json"});
  EXPECT_FALSE(fs::exists(path("h.png"))) << "the maps were generated before the stats check";
  expect_usage_error("render " + missing_scene + " --out " + missing_dir + "/img.png",
                     {missing_dir + "/img.png", "does not exist"});
  expect_usage_error("probe " + missing_scene + " --points " + path("missing.csv") + " --out " +
                         missing_dir + "/t.csv",
                     {missing_dir + "/t.csv"});
  expect_usage_error(
      "probe " + scene + " --points " + path("missing.csv") + " --out " + path("t.txt"),
      {"t.txt", ".csv"});
  expect_usage_error("voxelize " + missing_scene + " --out " + missing_dir + "/g.binvox",
                     {missing_dir + "/g.binvox"});
  expect_usage_error(
      "voxelize " + missing_scene + " --out " + path("g.binvox") + " --stats " + path("s.txt"),
      {"s.txt", ".json"});
  expect_usage_error("render " + missing_scene + " --out " + write("file", "x") + "/img.png",
                     {"img.png"});
  fs::create_directories(path("read_only"));
  fs::permissions(path("read_only"), fs::perms::owner_read | fs::perms::owner_exec);
  if (geteuid() != 0)  // root writes anywhere
    expect_usage_error("render " + missing_scene + " --out " + path("read_only") + "/img.png",
                       {"read_only/img.png", "permission denied"});
  fs::permissions(path("read_only"), fs::perms::owner_all);
}

}  // namespace
}  // namespace dv
