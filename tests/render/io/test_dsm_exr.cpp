// The deep-EXR export of deep shadow maps (render/io/deep_exr.h, render/io/dsm_export.h) round
// trip: every face's nodes, matrix and indices come back identical, lookups on the file's nodes
// answer what the storage answers, compositing the samples' alphas gives 1 - v, surface steps are
// two samples at one depth, and bad files fail with the file and the problem named.
#include <gtest/gtest.h>

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "experiments/source_paths.h"
#include "render/io/dsm_export.h"
#include "render/io/image.h"
#include "tests/engine/dsm/dsm_test_support.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  const fs::path dir = fs::path(test::binary_dir()) / "test_dsm_exr_tmp";
  fs::create_directories(dir);
  return (dir / name).string();
}

// Spot and omni (random translucent scene) plus a directional light: 8 faces.
SceneData three_lights() {
  test::SceneBuilder b;
  b.scene = test::random_scene(4);
  b.directional(dvec3(0.2, -1.0, 0.1));
  return b.build();
}

DeepShadowMaps generated(const SceneData& data, float eps, int res) {
  DsmSettings s;
  s.resolution = res;
  s.eps = eps;
  DeepShadowMaps maps(s);
  maps.generate(data, Backend::cpu);
  return maps;
}

void expect_message(const std::string& path, const std::string& problem) {
  try {
    read_deep_exr(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find(problem), std::string::npos) << m;
  }
}

TEST(DsmExr, RoundTripIsExactAndAnswersTheSameLookups) {
  const SceneData data = three_lights();
  const DeepShadowMaps maps = generated(data, 0.02f, 20);
  const DeepMapFile written = deep_map_file(maps, "abc123");
  ASSERT_EQ(written.faces.size(), 8u);
  const std::string path = temp_path("roundtrip.exr");
  write_deep_exr(path, written);
  const DeepMapFile read = read_deep_exr(path);
  EXPECT_EQ(read.eps, 0.02f);
  EXPECT_EQ(read.commit, "abc123");
  ASSERT_EQ(read.faces.size(), written.faces.size());
  const DsmReader reader = maps.storage().reader();
  size_t nodes = 0;
  for (size_t i = 0; i < read.faces.size(); ++i) {
    const DeepMapFace& w = written.faces[i];
    const DeepMapFace& r = read.faces[i];
    const ShadowFace& sf = maps.layout().faces[i];
    EXPECT_EQ(r.resolution, 20);
    EXPECT_EQ(r.light, w.light);
    EXPECT_EQ(r.face, w.face);
    EXPECT_EQ(r.orthographic, sf.orthographic);
    EXPECT_EQ(std::memcmp(r.world_to_clip.data(), &sf.projection.world_to_clip[0][0], 128), 0);
    ASSERT_EQ(r.offsets, w.offsets) << "face " << i;
    ASSERT_EQ(r.nodes.size(), w.nodes.size());
    nodes += r.nodes.size();
    for (size_t k = 0; k < r.nodes.size(); ++k) {
      EXPECT_EQ(r.nodes[k].z, w.nodes[k].z);
      EXPECT_EQ(r.nodes[k].v, w.nodes[k].v);
    }
    for (int64_t t = 0; t + 1 < int64_t(r.offsets.size()); ++t) {
      const DsmNode* n = r.nodes.data() + r.offsets[t];
      const int count = int(r.offsets[t + 1] - r.offsets[t]);
      const auto at = [n](int k) { return n[k]; };
      std::vector<float> zs = {0.0f, 1e6f};
      for (int k = 0; k < count; ++k) zs.insert(zs.end(), {n[k].z, n[k].z * 1.0001f});
      for (float z : zs) {
        int hint = -1;
        EXPECT_EQ(interpolate_nodes(at, count, lower_bound_nodes(at, count, z), z),
                  reader.visibility(sf.offset + t, z, hint));
      }
    }
  }
  EXPECT_GT(nodes, 0u);
  EXPECT_EQ(int64_t(nodes), maps.figures()["nodes"].get<int64_t>());
}

TEST(DsmExr, AlphasCompositeToAccumulatedOpacityAndStepsAreTwinSamples) {
  const SceneData data = three_lights();
  const DeepShadowMaps maps = generated(data, 0.0f, 12);
  const std::string path = temp_path("alpha.exr");
  write_deep_exr(path, deep_map_file(maps, ""));
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  OIIO::DeepData d;
  ASSERT_TRUE(in->read_native_deep_image(0, 0, d));
  int a = -1, z = -1, v = -1;
  for (int c = 0; c < d.channels(); ++c) {
    const std::string name(d.channelname(c));
    (name == "A" ? a : name == "Z" ? z : v) = c;
  }
  int64_t twins = 0;
  for (int64_t t = 0; t < 144; ++t) {
    double opacity = 0.0;
    for (int k = 0; k < d.samples(t); ++k) {
      opacity += (1.0 - opacity) * d.deep_value(t, a, k);
      EXPECT_NEAR(opacity, 1.0 - d.deep_value(t, v, k), 1e-5);
      if (k > 0) {
        EXPECT_GE(d.deep_value(t, z, k), d.deep_value(t, z, k - 1));
        twins += d.deep_value(t, z, k) == d.deep_value(t, z, k - 1);
      }
    }
  }
  EXPECT_GT(twins, 0);
}

TEST(DsmExr, BadFilesNameTheFileAndTheProblem) {
  expect_message(temp_path("missing.exr"), "not found");
  const std::string flat = temp_path("flat.exr");
  write_exr(flat, Image(4, 4));
  expect_message(flat, "not a deep image");
  const std::string no_v = temp_path("no_v.exr");
  {
    OIIO::ImageSpec spec(2, 2, 2, OIIO::TypeDesc::FLOAT);
    spec.deep = true;
    spec.channelnames = {"A", "Z"};
    spec.attribute("compression", "zips");
    OIIO::DeepData d;
    d.init(spec);
    auto out = OIIO::ImageOutput::create(no_v);
    ASSERT_TRUE(out && out->open(no_v, spec) && out->write_deep_image(d) && out->close());
  }
  expect_message(no_v, "no channel V");
  const std::string text = temp_path("text.exr");
  std::ofstream(text) << "not an image";
  expect_message(text, "cannot open");
}

}  // namespace
}  // namespace dv
