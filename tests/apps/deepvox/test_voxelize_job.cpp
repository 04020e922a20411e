// The `deepvox voxelize` command's functions: option parsing (resolution, bounds) with clear
// InputErrors, default cubic bounds, and whole jobs on a mesh file and a scene (binvox or .vdb
// and stats JSON written, metrics against exact).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "apps/deepvox/voxelize_job.h"
#include "core/error.h"
#include "experiments/source_paths.h"
#include "render/io/binvox.h"
#include "render/io/vdb_io.h"
#include "render/load/scene_loader.h"
#include "strategies/voxelizer/triangle_soup.h"

namespace dv {
namespace {

std::string scratch_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "deepvox_test_voxelize_job";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void expect_input_error(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError mentioning '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(VoxelizeJob, ParsesResolutions) {
  EXPECT_EQ(parse_voxel_resolution("512x512x32"), ivec3(512, 512, 32));
  EXPECT_EQ(parse_voxel_resolution("64"), ivec3(64, 64, 64));
  EXPECT_EQ(parse_voxel_resolution("7x5x1024"), ivec3(7, 5, 1024));
  expect_input_error([] { parse_voxel_resolution("512x512x30"); }, "multiple of 32");
  expect_input_error([] { parse_voxel_resolution("0x512x32"); }, "positive");
  expect_input_error([] { parse_voxel_resolution("512x512x8192"); }, "too big");
  expect_input_error([] { parse_voxel_resolution("512x512"); }, "WxHxD");
  expect_input_error([] { parse_voxel_resolution("a12x512x32"); }, "--res");
  expect_input_error([] { parse_voxel_resolution("-4x4x32"); }, "--res");
  expect_input_error([] { parse_voxel_resolution("99999999999x4x32"); }, "--res");
}

TEST(VoxelizeJob, ParsesBounds) {
  const Aabb b = parse_voxel_bounds("-1,0.5,2,3,4.5,6e0");
  EXPECT_EQ(b.lo, dvec3(-1.0, 0.5, 2.0));
  EXPECT_EQ(b.hi, dvec3(3.0, 4.5, 6.0));
  expect_input_error([] { parse_voxel_bounds("0,0,0,1,1"); }, "six numbers");
  expect_input_error([] { parse_voxel_bounds("0,0,0,1,x,1"); }, "not a finite number");
  expect_input_error([] { parse_voxel_bounds("0,0,0,1,1,inf"); }, "not a finite number");
  expect_input_error([] { parse_voxel_bounds("0,0,0,1,0,1"); }, "upper corner");
  expect_input_error([] { parse_voxel_bounds("0,0,0,1,1,1,"); }, "--bounds");
}

TEST(VoxelizeJob, CubicBoundsKeepTheCentre) {
  const Aabb c = cubic_bounds(Aabb{dvec3(0.0, -1.0, 2.0), dvec3(4.0, 1.0, 3.0)}, "m");
  EXPECT_EQ(c.lo, dvec3(0.0, -2.0, 0.5));
  EXPECT_EQ(c.hi, dvec3(4.0, 2.0, 4.5));
  expect_input_error([] { cubic_bounds(Aabb{}, "empty.obj"); }, "empty.obj");
  expect_input_error([] { cubic_bounds(Aabb{dvec3(1.0), dvec3(1.0)}, "point.obj"); }, "--bounds");
}

TEST(VoxelizeJob, MeshFileToBinvoxAndStats) {
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  job.method = "sat";
  job.backend = "cpu";
  job.res = "64x64x64";
  job.out = scratch_file("bunny.binvox");
  job.stats = scratch_file("bunny.json");
  job.compare_exact = true;
  const nlohmann::json stats = run_voxelize_job(job, [](Backend) {
    return nlohmann::json{{"tool", "test"}};
  });
  EXPECT_EQ(stats["method"], "sat");
  EXPECT_EQ(stats["backend"], "cpu");
  EXPECT_EQ(stats["res"], nlohmann::json({64, 64, 64}));
  EXPECT_EQ(stats["triangles"].get<int64_t>(), 3674);
  EXPECT_EQ(stats["meta"]["tool"], "test");
  const int64_t filled = stats["filled"].get<int64_t>();
  EXPECT_GT(filled, 2000);
  EXPECT_EQ(stats["exact"]["metrics"]["missing_outside_band"].get<int64_t>(), 0);
  EXPECT_EQ(stats["exact"]["metrics"]["filled"].get<int64_t>(), filled);
  ASSERT_TRUE(stats["passes"].is_array());
  EXPECT_EQ(stats["passes"].back()["pass"], "large");
  // Default bounds: the mesh's box made cubic, the same side on every axis.
  const auto lo = stats["bounds"]["min"].get<std::vector<double>>();
  const auto hi = stats["bounds"]["max"].get<std::vector<double>>();
  EXPECT_NEAR(hi[0] - lo[0], hi[1] - lo[1], 1e-12);
  EXPECT_NEAR(hi[0] - lo[0], hi[2] - lo[2], 1e-12);

  const BinvoxFile file = read_binvox(job.out);
  EXPECT_EQ(file.grid.popcount(), filled);
  EXPECT_NEAR(file.translate.x, lo[0], 1e-12);
  EXPECT_NEAR(file.scale, hi[0] - lo[0], 1e-12);
  std::ifstream written(job.stats);
  EXPECT_EQ(nlohmann::json::parse(written)["filled"].get<int64_t>(), filled);
}

// The grid as a .vdb (full build), read back as a scene volume: the set voxels are the samples
// of 1, the first voxel's centre sits at bounds.lo + half a voxel. The lean build says it cannot.
TEST(VoxelizeJob, MeshFileToVdb) {
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  job.backend = "cpu";
  job.res = "32x32x32";
  job.bounds = "-1,-1,-1,1,1,1";
  job.out = scratch_file("bunny.vdb");
  std::filesystem::remove(job.out);
  if (!vdb_supported()) {
    expect_input_error([&] { run_voxelize_job(job); }, "built without OpenVDB");
    EXPECT_FALSE(std::filesystem::exists(job.out));
    return;
  }
  const nlohmann::json stats = run_voxelize_job(job);
  EXPECT_EQ(stats["vdb"]["grid"], "density");
  EXPECT_FALSE(stats.contains("binvox"));
  const VolumeGrid volume = load_vdb_volume(job.out);
  int64_t ones = 0;
  for (float d : volume.density) ones += d == 1.0f;
  EXPECT_EQ(ones, stats["filled"].get<int64_t>());
  EXPECT_GT(ones, 100);
  const double voxel = 2.0 / 32;
  EXPECT_NEAR(volume.spacing.x, voxel, 1e-12);
  // The loaded box starts one voxel before the first set voxel, on the voxel-centre lattice.
  for (int a = 0; a < 3; ++a) {
    const double cells = (volume.origin[a] - (-1.0 + 0.5 * voxel)) / voxel;
    EXPECT_NEAR(cells, std::round(cells), 1e-9) << a;
  }
}

TEST(VoxelizeJob, SceneWithGivenBoundsAndExactMethod) {
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/scenes/translucent-boxes.json";
  job.method = "exact";
  job.backend = "cpu";
  job.res = "32x32x32";
  job.bounds = "-3,-3,-3,3,3,3";
  const nlohmann::json stats = run_voxelize_job(job);
  const Scene scene = load_scene(job.input);
  EXPECT_EQ(stats["triangles"].get<int64_t>(), triangle_soup(scene).triangle_count());
  EXPECT_EQ(stats["bounds"]["min"], nlohmann::json({-3.0, -3.0, -3.0}));
  EXPECT_EQ(stats["voxel_size"], nlohmann::json({6.0 / 32, 6.0 / 32, 6.0 / 32}));
  EXPECT_GT(stats["filled"].get<int64_t>(), 0);
  EXPECT_FALSE(stats.contains("binvox"));
}

TEST(VoxelizeJob, BadJobsAreInputErrors) {
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  job.backend = "cpu";
  job.res = "32x32x32";
  VoxelizeJob unknown = job;
  unknown.method = "voxelmagic";
  expect_input_error([&] { run_voxelize_job(unknown); },
                     "known: atlas, atlas-compute, exact, sat, slicemap");
  VoxelizeJob bad_res = job;
  bad_res.res = "32x32x33";
  expect_input_error([&] { run_voxelize_job(bad_res); }, "--res");
  VoxelizeJob bad_bounds = job;
  bad_bounds.bounds = "1,1,1,0,0,0";
  expect_input_error([&] { run_voxelize_job(bad_bounds); }, "--bounds");
  VoxelizeJob exact_on_gpu = job;
  exact_on_gpu.method = "exact";
  exact_on_gpu.backend = "cuda";
  expect_input_error([&] { run_voxelize_job(exact_on_gpu); }, "exact");
  VoxelizeJob missing = job;
  missing.input = scratch_file("no_such_mesh.obj");
  expect_input_error([&] { run_voxelize_job(missing); }, "no_such_mesh.obj");
  VoxelizeJob unwritable = job;
  unwritable.out = scratch_file("no_such_dir/grid.binvox");
  expect_input_error([&] { run_voxelize_job(unwritable); }, "grid.binvox");
  VoxelizeJob bad_param = job;
  bad_param.params = {"tiles=4"};
  expect_input_error([&] { run_voxelize_job(bad_param); }, "tiles");
}

}  // namespace
}  // namespace dv
