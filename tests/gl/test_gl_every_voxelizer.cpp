// Every OpenGL voxelizer (gl::register_gl_voxelizers, names from its registry): creation with
// defaults, the parameter round trip, an empty soup gives an empty grid, and one triangle gives
// the same grid as the CPU voxelizer of the same name, bit for bit. Skipped with the reason
// where no headless OpenGL 4.5 context can be made.
#include <gtest/gtest.h>

#include "gl/gl_voxelizers.h"
#include "tests/gl/gl_test_support.h"

namespace dv {
namespace {

const Registry<Voxelizer>& gl_voxelizers() {
  static const Registry<Voxelizer> registry =
      make_registry<Voxelizer>("voxelizer with --backend gl", {gl::register_gl_voxelizers});
  return registry;
}

class EveryGlVoxelizer : public test::GlContextTest,
                         public ::testing::WithParamInterface<std::string> {};

TEST_P(EveryGlVoxelizer, RoundTripsAndMatchesTheCpu) {
  const std::string& name = GetParam();
  const auto made = gl_voxelizers().create(name);
  std::vector<std::string> items;
  const nlohmann::json echoed = made->params();
  for (const auto& [key, value] : echoed.items()) items.push_back(key + "=" + value.dump());
  EXPECT_EQ(gl_voxelizers().create(name, StrategyParams::parse(items))->params(), echoed);

  const GridSpec spec = make_box_grid({32, 32, 32}, {dvec3(0.0), dvec3(1.0)});
  EXPECT_EQ(made->voxelize(Backend::cpu, TriangleSoup{}, spec).grid.popcount(), 0);
  TriangleSoup one;
  one.add({0.1, 0.2, 0.3}, {0.9, 0.25, 0.5}, {0.4, 0.85, 0.7});
  const VoxelizeResult gl = made->voxelize(Backend::cpu, one, spec);
  const VoxelizeResult cpu = voxelizer_registry().create(name)->voxelize(Backend::cpu, one, spec);
  EXPECT_GT(gl.grid.popcount(), 0);
  EXPECT_EQ(test::count_differences(cpu.grid, gl.grid, name), 0);
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryGlVoxelizer, ::testing::ValuesIn(gl_voxelizers().names()),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace dv
