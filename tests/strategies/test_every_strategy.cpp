// Every registered strategy of every family, on every backend: the suites are instantiated from
// the registries' names() crossed with cpu and cuda (cuda skipped with the reason where no GPU
// can be used), so a newly registered shadow method, storage or voxelizer is tested with no
// other edit. Each checks: creation with defaults; its params() fed back into creation gives
// the same params(); sane output on a small scene (transmittance finite and in [0, 1], or a
// grid that holds the triangle and nothing for an empty soup); and on cuda the CPU answers
// within the parity tolerance (1e-5 on transmittance: the two sides build the same maps from
// the same float operations; grids bit for bit).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"
#include "tests/support/backends.h"

namespace dv {
namespace {

using NameAndBackend = std::tuple<std::string, Backend>;

std::string test_name(const ::testing::TestParamInfo<NameAndBackend>& info) {
  std::string name = std::get<0>(info.param) + "_" + to_string(std::get<1>(info.param));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// A strategy's echoed parameters as the key=value items its factory reads.
std::vector<std::string> as_items(const nlohmann::json& params) {
  std::vector<std::string> items;
  for (const auto& [key, value] : params.items())
    items.push_back(key + "=" + (value.is_string() ? value.get<std::string>() : value.dump()));
  return items;
}

template <class Base>
void expect_params_round_trip(const Registry<Base>& registry, const std::string& name,
                              const std::vector<std::string>& first = {}) {
  const auto made = registry.create(name, StrategyParams::parse(first));
  const nlohmann::json echoed = made->params();
  for (const ParamSpec& spec : registry.params(name))  // every declared key is echoed
    if (spec.type != ParamSpec::Type::nested && !spec.fallback.empty())
      EXPECT_TRUE(echoed.contains(spec.key)) << name << " does not echo " << spec.key;
  for (const auto& [key, value] : echoed.items()) {  // and nothing else but nested keys
    bool declared = false;
    for (const ParamSpec& spec : registry.params(name))
      declared = declared || key == spec.key ||
                 (spec.type == ParamSpec::Type::nested && key.rfind(spec.key + ".", 0) == 0);
    EXPECT_TRUE(declared) << name << " echoes the undeclared key " << key;
  }
  const auto again = registry.create(name, StrategyParams::parse(as_items(echoed)));
  EXPECT_EQ(again->params(), echoed) << echoed.dump();
}

std::vector<dvec3> probe_points(const Scene& scene, int count) {
  const Aabb b = world_bounds(scene);
  std::mt19937 rng(11);
  std::vector<dvec3> points;
  for (int i = 0; i < count; ++i) {
    dvec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<double>(b.lo[a], b.hi[a])(rng);
    points.push_back(p);
  }
  return points;
}

// The answers of shadow method `name` (with `params`) at points in the small translucent scene.
std::vector<double> probe(const std::string& name, const std::vector<std::string>& params,
                          Backend backend) {
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/translucent-boxes.json");
  const SceneData data(scene, memory_of(backend));
  auto method = shadow_registry().create(name, StrategyParams::parse(params));
  return probe_transmittance(backend, data, *method, probe_points(scene, 400)).transmittance;
}

void expect_sane_and_matching_cpu(const std::string& name, const std::vector<std::string>& params,
                                  Backend backend) {
  const std::vector<double> t = probe(name, params, backend);
  ASSERT_FALSE(t.empty());
  for (double v : t) {
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 1.0);
  }
  if (backend == Backend::cpu) return;
  const std::vector<double> cpu = probe(name, params, Backend::cpu);
  ASSERT_EQ(cpu.size(), t.size());
  double worst = 0.0;
  for (size_t i = 0; i < t.size(); ++i) worst = std::max(worst, std::abs(cpu[i] - t[i]));
  EXPECT_LE(worst, 1e-5) << name << ": largest CPU/CUDA difference";
}

class EveryShadowMethod : public ::testing::TestWithParam<NameAndBackend> {};

TEST_P(EveryShadowMethod, CreatesRoundTripsAndAnswersSanely) {
  const auto& [name, backend] = GetParam();
  DV_SKIP_UNLESS_BACKEND(backend);
  expect_params_round_trip(shadow_registry(), name);
  expect_sane_and_matching_cpu(name, {}, backend);
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryShadowMethod,
                         ::testing::Combine(::testing::ValuesIn(shadow_registry().names()),
                                            ::testing::ValuesIn(test::all_backends())),
                         test_name);

class EveryStorage : public ::testing::TestWithParam<NameAndBackend> {};

TEST_P(EveryStorage, CreatesRoundTripsAndAnswersSanely) {
  const auto& [name, backend] = GetParam();
  DV_SKIP_UNLESS_BACKEND(backend);
  expect_params_round_trip(storage_registry(), name);
  // The methods that take a storage echo its parameters as storage.KEY.
  for (const char* method : {"dsm", "auto"})
    expect_params_round_trip(shadow_registry(), method, {"storage=" + name});
  expect_sane_and_matching_cpu("dsm", {"storage=" + name, "res=64"}, backend);
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryStorage,
                         ::testing::Combine(::testing::ValuesIn(storage_registry().names()),
                                            ::testing::ValuesIn(test::all_backends())),
                         test_name);

class EveryVoxelizer : public ::testing::TestWithParam<NameAndBackend> {};

TEST_P(EveryVoxelizer, CreatesRoundTripsAndVoxelizesSanely) {
  const auto& [name, backend] = GetParam();
  DV_SKIP_UNLESS_BACKEND(backend);
  expect_params_round_trip(voxelizer_registry(), name);
  auto voxelizer = voxelizer_registry().create(name);
  if (!voxelizer->supports(backend))
    GTEST_SKIP() << "voxelizer '" << name << "' does not run on " << to_string(backend);
  const GridSpec spec = make_box_grid({32, 32, 32}, {dvec3(0.0), dvec3(1.0)});

  const VoxelizeResult empty = voxelizer->voxelize(backend, TriangleSoup{}, spec);
  EXPECT_EQ(empty.grid.popcount(), 0);

  TriangleSoup one;
  one.add({0.1, 0.2, 0.3}, {0.9, 0.25, 0.5}, {0.4, 0.85, 0.7});
  const VoxelizeResult got = voxelizer->voxelize(backend, one, spec);
  EXPECT_GT(got.grid.popcount(), 0);
  if (backend == Backend::cpu) return;
  const VoxelizeResult cpu = voxelizer->voxelize(Backend::cpu, one, spec);
  EXPECT_EQ(cpu.grid.words(), got.grid.words()) << name << ": CPU and CUDA grids differ";
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryVoxelizer,
                         ::testing::Combine(::testing::ValuesIn(voxelizer_registry().names()),
                                            ::testing::ValuesIn(test::all_backends())),
                         test_name);

// The round trip above with defaults, here with every key of the dsm method given a value other
// than its default: each is read into the settings and echoed as given (one table declares,
// reads and writes them, strategies/storage/deep_shadow_maps.cpp).
TEST(DsmMethod, EveryKeyEchoedAsGiven) {
  const std::vector<std::string> items = {"storage=chunked", "res=48",
                                          "eps=0.125",       "filter=bilinear",
                                          "bias=0.25",       "slope=1.5",
                                          "subrays=4",       "volume=table",
                                          "table_bins=16",   "step_scale=0.75",
                                          "clusters=3",      "cluster_d0=0.125",
                                          "lispsm=1",        "cluster_hysteresis=0.375"};
  const nlohmann::json echoed =
      shadow_registry().create("dsm", StrategyParams::parse(items))->params();
  for (const std::string& item : items) {
    const size_t equals = item.find('=');
    const std::string key = item.substr(0, equals), given = item.substr(equals + 1);
    ASSERT_TRUE(echoed.contains(key)) << key;
    const nlohmann::json& value = echoed[key];
    EXPECT_EQ(value.is_string() ? value.get<std::string>() : value.dump(), given) << key;
  }
}

TEST(Registries, RegisteringANameTwiceIsAnError) {
  Registry<Voxelizer> registry("voxelizer");
  const auto make = [](const StrategyParams&) -> std::unique_ptr<Voxelizer> { return nullptr; };
  registry.add("twin", "first", {}, make);
  EXPECT_THROW(registry.add("Twin", "second", {}, make), Error);
}

}  // namespace
}  // namespace dv
