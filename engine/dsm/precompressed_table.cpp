// build_precompressed_tables (see precompressed_table.h): per volume object and density-node
// pair, V(u) = exp(-step tau(u)) on 512 sub-steps with tau exact (transfer_sigma_mean), node
// positions from the DSM compressor (its eps raised by half until at most kTableNodes interior
// nodes remain). A table depends only on the transfer function, the step, the bins and eps, so
// it is pre-computed once per process and reused (Hadwiger pre-computes it once per transfer
// function); without the cache every generation rebuilt it on the host, 8-30x the GPU
// generation time in the seeds run of 2026-12-01.
#include "engine/dsm/precompressed_table.h"

#include <cmath>
#include <map>
#include <mutex>

#include "cuda/buffer.h"
#include "engine/dsm/visibility_compressor.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

namespace {

constexpr int kFineSteps = 512;

PrecompressedStep tabulate(const ObjectView& o, const TransferPoint* tf, double d0, double d1,
                           float eps) {
  std::vector<float> visibility(kFineSteps + 1);
  for (int k = 0; k <= kFineSteps; ++k) {
    const double u = double(k) / kFineSteps;
    const double tau = u * transfer_sigma_mean(tf, o.transfer_count, d0, d0 + (d1 - d0) * u);
    visibility[size_t(k)] = float(std::exp(-o.step * tau));
  }
  for (;; eps *= 1.5f) {
    float z[kTableNodes + 8], v[kTableNodes + 8];
    VisibilityCompressor<ArrayNodeSink> c(eps, ArrayNodeSink{z, v, kTableNodes + 8});
    for (int k = 0; k <= kFineSteps; ++k) c.push(float(k) / kFineSteps, visibility[size_t(k)]);
    c.finish();
    int inner = 0;
    for (int i = 0; i < c.sink().count; ++i) inner += z[i] > 0.0f && z[i] < 1.0f;
    if (c.stats().overflow || inner > kTableNodes) continue;
    PrecompressedStep step{};
    for (int i = 0; i < c.sink().count; ++i)
      if (z[i] > 0.0f && z[i] < 1.0f) step.s[step.count++] = z[i];
    return step;
  }
}

// What a scene's tables depend on: bins, eps, and per object its interior, step and transfer
// function's densities and extinctions.
std::vector<double> table_key(const std::vector<ObjectView>& objects,
                              const std::vector<TransferPoint>& transfer, int bins, float eps) {
  std::vector<double> key = {double(bins), double(eps)};
  for (const ObjectView& o : objects) {
    key.push_back(o.interior == InteriorKind::volume ? o.step : -1.0);
    if (o.interior != InteriorKind::volume) continue;
    key.push_back(double(o.transfer_count));
    for (int k = 0; k < o.transfer_count; ++k) {
      key.push_back(transfer[size_t(o.transfer_first + k)].density);
      key.push_back(transfer[size_t(o.transfer_first + k)].sigma);
    }
  }
  return key;
}

}  // namespace

PrecompressedTableData build_precompressed_tables(const SceneData& scene, int bins,
                                                  float table_eps) {
  const std::vector<ObjectView> objects = to_host_vector(scene.view().objects, scene.memory());
  const std::vector<TransferPoint> transfer = to_host_vector(scene.view().transfer, scene.memory());
  constexpr size_t kCachedTables = 16;
  static std::mutex mutex;
  static std::map<std::vector<double>, PrecompressedTableData> cache;
  const std::vector<double> key = table_key(objects, transfer, bins, table_eps);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(key);
    if (found != cache.end()) return found->second;
  }
  PrecompressedTableData data;
  for (const ObjectView& o : objects) {
    if (o.interior != InteriorKind::volume || o.transfer_count < 1) {
      data.object_table.push_back(-1);
      data.domain.push_back(dvec2(0.0));
      continue;
    }
    const TransferPoint* tf = transfer.data() + o.transfer_first;
    dvec2 domain(tf[0].density, tf[o.transfer_count - 1].density);
    if (!(domain.y > domain.x)) domain.y = domain.x + 1.0;
    data.object_table.push_back(int32_t(data.steps.size()));
    data.domain.push_back(domain);
    const auto node = [&](int i) { return domain.x + (domain.y - domain.x) * i / (bins - 1); };
    for (int i = 0; i < bins; ++i)
      for (int j = 0; j < bins; ++j)
        data.steps.push_back(tabulate(o, tf, node(i), node(j), table_eps));
  }
  const std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= kCachedTables) cache.clear();
  cache.emplace(key, data);
  return data;
}

}  // namespace dv
