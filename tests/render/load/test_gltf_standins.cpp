// The glTF stand-ins committed under experiments/assets/gltf/ (docs/images/feature_standins.py):
// they are the generator's output, not hand edits, and each loads with the effect it stands in
// for (red glass, an alpha-masked textured quad, a tinted medium behind glass, a textured and
// normal-mapped torus without lights, which is staged).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"

namespace dv {
namespace {

std::string asset(const std::string& name) {
  return test::source_dir() + "/experiments/assets/gltf/" + name;
}

const Object& object_named(const Scene& scene, const std::string& name) {
  for (const Object& o : scene.objects)
    if (o.name == name) return o;
  ADD_FAILURE() << "no object named " << name << " in " << scene.source;
  return scene.objects.front();
}

TEST(GltfStandIns, CommittedFilesAreTheGeneratorsOutput) {
  if (std::system("python3 --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  const std::string check =
      "python3 " + test::source_dir() + "/docs/images/feature_standins.py --check " + asset("");
  EXPECT_EQ(std::system(check.c_str()), 0) << check;
}

TEST(GltfStandIns, EachLoadsWithTheEffectItStandsIn) {
  const Scene slab = load_scene(asset("red-glass-slab.gltf"));
  const Object& glass = object_named(slab, "red glass");
  EXPECT_DOUBLE_EQ(glass.material.transmission, 1.0);
  EXPECT_GT(glass.material.color.x, 5.0 * glass.material.color.y);  // red
  ASSERT_EQ(slab.lights.size(), 1u);  // its own spot light: not staged, no ground
  EXPECT_EQ(slab.lights[0].type, LightType::spot);
  EXPECT_EQ(slab.objects.size(), 3u);

  const Scene quad = load_scene(asset("alpha-mask-quad.gltf"));
  object_named(quad, "cut-out quad");
  EXPECT_EQ(quad.lights.size(), 1u);

  const Scene tinted = load_scene(asset("tinted-medium-glass.gltf"));
  const Object& medium = object_named(tinted, "blue medium");
  EXPECT_EQ(medium.interior.kind, InteriorKind::constant);
  EXPECT_LT(medium.interior.sigma_tint.z, medium.interior.sigma_tint.x);  // blue passes
  EXPECT_DOUBLE_EQ(object_named(tinted, "glass pane").material.transmission, 1.0);
  EXPECT_EQ(object_named(tinted, "glass pane").interior.kind, InteriorKind::none);

  const Scene torus = load_scene(asset("textured-torus.gltf"));
  object_named(torus, "torus");
  EXPECT_EQ(torus.lights.size(), 2u);  // staged: key and fill
  EXPECT_EQ(torus.objects.back().name, "ground");
}

}  // namespace
}  // namespace dv
