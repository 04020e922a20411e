// compact generates its faces in sets whose replay scratch and records fit a budget
// (strategies/storage/compact_storage.cpp). knecht-32-lights (112 faces) in sets of one face, of
// several faces ending off a group of starts (rounded to whole groups), with the last set
// partial, and clustered (per-face object masks): the very bits of one set of all faces, in the
// nodes and their starts, every record, the figures, every lookup and a rendered frame. A
// generation in sets that does not keep its records answers figures only. On the CPU threads and
// on CUDA (skipped without a GPU).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "render/frame/raster_render.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/node_replay_scratch.h"
#include "tests/strategies/storage/storage_test_support.h"

namespace dv {
namespace {

using test::Generated;

// Answers with maps generated beforehand, so that a frame renders with them as they are.
class GeneratedMaps final : public ShadowMethod {
 public:
  explicit GeneratedMaps(const DeepShadowMaps& maps) : maps_(maps) {}
  std::string name() const override { return "generated"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  ShadowSourceVariant prepare(const SceneData&, Backend, const Camera*) override {
    return maps_.source();
  }

 private:
  const DeepShadowMaps& maps_;
};

std::vector<float> rendered(const Scene& scene, const Generated& g, Backend backend) {
  Camera camera = scene.camera;
  camera.width = 48, camera.height = 32;
  GeneratedMaps method(*g.maps);
  return render_raster(backend, *g.data, camera, method, scene.background).render.image.rgb;
}

Generated generate_maps(const Scene& scene, Backend backend, DsmSettings s) {
  Generated g;
  g.data = std::make_unique<SceneData>(scene, memory_of(backend));
  g.maps = std::make_unique<DeepShadowMaps>(std::move(s));
  g.maps->generate(*g.data, backend);
  return g;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// The set's budget for `faces` faces of res^2 texels.
int64_t budget_of(int64_t faces, int res) {
  return faces * res * res * (kReplayBytesPerTexel + int64_t(sizeof(DsmTexelRecord)));
}

struct SetCase {
  int res;
  int clusters;
  int64_t set_bytes;
  int64_t sets;  // expected for 112 faces; -1: more than one
};

TEST(CompactFaceSets, SameBitsAsOneSet) {
  std::vector<Backend> backends = {Backend::cpu};
  if (cuda_device_available()) backends.push_back(Backend::cuda);
  const Scene scene = test::scene_file("knecht-32-lights.json");
  const SetCase cases[] = {
      {8, 1, 1, 112},                  // one face a set
      {12, 1, budget_of(12, 12), 10},  // 144 texels a face: steps of 4 faces, last set of 4
      {5, 1, 1, 2},                    // 25 texels a face: steps of 64 faces
      {8, 2, 1, -1}};                  // clustered (their own resolution): several sets
  for (const Backend backend : backends)
    for (const SetCase& c : cases) {
      DsmSettings s = test::storage_settings("compact", {}, 0.02f, c.res);
      s.clusters.max_clusters = c.clusters;
      s.keep_records = true;
      const Generated one = generate_maps(scene, backend, s);
      s.face_set_bytes = c.set_bytes;
      const Generated sets = generate_maps(scene, backend, s);
      const std::string where = std::string(to_string(backend)) + " res " + std::to_string(c.res) +
                                " clusters " + std::to_string(c.clusters);
      nlohmann::json want = one.maps->figures(), got = sets.maps->figures();
      ASSERT_EQ(want["strategy"]["face_sets"], 1) << where;
      if (c.sets > 0)
        ASSERT_EQ(got["strategy"]["face_sets"], c.sets) << where;
      else
        ASSERT_GT(got["strategy"]["face_sets"].get<int64_t>(), 1) << where;
      EXPECT_LT(got["strategy"]["replay_scratch_bytes"].get<int64_t>(),
                want["strategy"]["replay_scratch_bytes"].get<int64_t>())
          << where;
      want.erase("strategy");
      got.erase("strategy");
      EXPECT_EQ(got, want) << where;
      EXPECT_GT(want["nodes"].get<int64_t>(), 0) << where;
      const DsmHostNodes a = one.maps->storage().host_nodes(),
                         b = sets.maps->storage().host_nodes();
      EXPECT_TRUE(same_bits(a.offsets, b.offsets)) << where;
      EXPECT_TRUE(same_bits(a.nodes, b.nodes)) << where;
      EXPECT_TRUE(same_bits(one.maps->records(), sets.maps->records())) << where;
      EXPECT_TRUE(
          same_bits(test::sample_lookups(one, backend), test::sample_lookups(sets, backend)))
          << where;
      EXPECT_TRUE(same_bits(rendered(scene, one, backend), rendered(scene, sets, backend)))
          << where;
    }
}

TEST(CompactFaceSets, RecordsNotKeptLeaveTheFigures) {
  const Scene scene = test::scene_file("knecht-32-lights.json");
  DsmSettings s = test::storage_settings("compact", {}, 0.02f, 8);
  const Generated one = generate_maps(scene, Backend::cpu, s);
  EXPECT_EQ(one.maps->records().size(), size_t(112 * 8 * 8));  // one set: copied on demand
  s.face_set_bytes = 1;
  const Generated sets = generate_maps(scene, Backend::cpu, s);
  EXPECT_THROW(sets.maps->records(), Error);
  nlohmann::json want = one.maps->figures(), got = sets.maps->figures();
  want.erase("strategy");
  got.erase("strategy");
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace dv
