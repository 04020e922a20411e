// Determinism: the same scene rendered 10 times gives bit-identical images (dsm
// shadows on compact storage and on chunked storage whose chunk claims race, alloc=thesis),
// identical per-texel node counts and node lists, and identical voxel grids (sat, slicemap).
// Run on the CPU's threads and, where a GPU is present, on CUDA (skipped with the reason
// otherwise); scripts/gpu-check.sh runs test_hard on the GPU node.
#include <gtest/gtest.h>

#include <cstring>

#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/voxelizer/sat_voxelizer.h"
#include "strategies/voxelizer/slicemap_voxelizer.h"
#include "strategies/voxelizer/triangle_soup.h"
#include "tests/hard/hard_test_support.h"
#include "tests/strategies/storage/storage_test_support.h"

namespace dv::test {
namespace {

constexpr int kRuns = 10;

Scene small_demo() {
  Scene scene = load_scene(source_dir() + "/experiments/scenes/demo.json");
  scene.camera.width = 96;
  scene.camera.height = 72;
  return scene;
}

std::vector<float> render_dsm(Backend backend, const Scene& scene,
                              const std::vector<std::string>& storage) {
  const SceneData data(scene, memory_of(backend));
  std::vector<std::string> params = {"res=128", "eps=0.01"};
  params.insert(params.end(), storage.begin(), storage.end());
  const auto method = shadow_registry().create("dsm", StrategyParams::parse(params));
  return render_raster(backend, data, scene.camera, *method, scene.background).render.image.rgb;
}

class HardDeterminism : public HardOnBackends {};

TEST_P(HardDeterminism, RenderedImagesAreBitIdentical) {
  const Scene scene = small_demo();
  for (const std::vector<std::string>& storage :
       {std::vector<std::string>{"storage=compact"},
        std::vector<std::string>{"storage=chunked", "storage.alloc=thesis"}}) {
    const std::vector<float> first = render_dsm(GetParam(), scene, storage);
    for (int run = 1; run < kRuns; ++run) {
      const std::vector<float> again = render_dsm(GetParam(), scene, storage);
      ASSERT_EQ(again.size(), first.size());
      EXPECT_EQ(std::memcmp(again.data(), first.data(), first.size() * sizeof(float)), 0)
          << storage.front() << " run " << run;
    }
  }
}

// Per texel: node counts, stored nodes, error and flags, and the visibility at 24 depths
// through the storage's reader (chunked storage places the nodes wherever its chunk claims
// land, so its functions are compared through lookups); compact's node lists themselves too.
TEST_P(HardDeterminism, NodeCountsAndNodesAreIdentical) {
  const Scene scene = small_demo();
  for (const std::vector<std::string>& params :
       {std::vector<std::string>{}, std::vector<std::string>{"alloc=thesis"}}) {
    DsmSettings settings = unbiased_settings(0.01f, 64);
    settings.storage = params.empty() ? "compact" : "chunked";
    settings.storage_params = StrategyParams::parse(params);
    const HardMaps first = generate_maps(scene, GetParam(), settings);
    const std::vector<float> first_lookups = texel_lookups(*first.maps, *first.data, GetParam());
    for (int run = 1; run < kRuns; ++run) {
      const HardMaps again = generate_maps(scene, GetParam(), settings);
      const auto& a = first.maps->records();
      const auto& b = again.maps->records();
      ASSERT_EQ(a.size(), b.size());
      for (size_t i = 0; i < a.size(); ++i)
        ASSERT_TRUE(a[i].nodes == b[i].nodes && a[i].stored == b[i].stored &&
                    a[i].error == b[i].error && a[i].flags == b[i].flags)
            << settings.storage << " run " << run << " texel " << i;
      const std::vector<float> lookups = texel_lookups(*again.maps, *again.data, GetParam());
      ASSERT_EQ(lookups.size(), first_lookups.size());
      EXPECT_EQ(std::memcmp(lookups.data(), first_lookups.data(), lookups.size() * sizeof(float)),
                0)
          << settings.storage << " run " << run;
      if (settings.storage != "compact") continue;
      const DsmHostNodes nodes = again.maps->storage().host_nodes();
      const DsmHostNodes first_nodes = first.maps->storage().host_nodes();
      ASSERT_EQ(nodes.offsets, first_nodes.offsets) << "run " << run;
      ASSERT_EQ(nodes.nodes.size(), first_nodes.nodes.size());
      EXPECT_EQ(std::memcmp(nodes.nodes.data(), first_nodes.nodes.data(),
                            nodes.nodes.size() * sizeof(DsmNode)),
                0)
          << "run " << run;
    }
  }
}

TEST_P(HardDeterminism, VoxelGridsAreIdentical) {
  const TriangleSoup soup = triangle_soup(small_demo());
  const GridSpec spec = make_box_grid({96, 80, 64}, soup.bounds());
  for (const char* name : {"sat", "slicemap"}) {
    const auto voxelizer = voxelizer_registry().create(name);
    const std::vector<uint32_t> first = voxelizer->voxelize(GetParam(), soup, spec).grid.words();
    for (int run = 1; run < kRuns; ++run)
      EXPECT_EQ(voxelizer->voxelize(GetParam(), soup, spec).grid.words(), first)
          << name << " run " << run;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, HardDeterminism, ::testing::Values(Backend::cpu, Backend::cuda),
                         BackendName());

}  // namespace
}  // namespace dv::test
