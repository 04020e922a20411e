// build_precompressed_tables (see precompressed_table.h): per volume object and density-bin
// pair, tau(s) by the midpoint rule on 512 sub-steps, node positions from the DSM compressor
// (its eps raised by half until at most kTableNodes interior nodes remain), tau at those
// positions from the fine table.
#include "engine/dsm/precompressed_table.h"

#include <cmath>

#include "cuda/buffer.h"
#include "engine/dsm/visibility_compressor.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

namespace {

constexpr int kFineSteps = 512;

// Node positions (interior, in (0, 1)) the compressor keeps for V(u) = exp(-step tau(u)).
std::vector<float> node_positions(const std::vector<double>& tau, double step, float eps) {
  for (;; eps *= 1.5f) {
    float z[kTableNodes + 8], v[kTableNodes + 8];
    VisibilityCompressor<ArrayNodeSink> c(eps, ArrayNodeSink{z, v, kTableNodes + 8});
    for (int k = 0; k <= kFineSteps; ++k)
      c.push(float(k) / kFineSteps, float(std::exp(-step * tau[size_t(k)])));
    c.finish();
    std::vector<float> inner;
    for (int i = 0; i < c.sink().count; ++i)
      if (z[i] > 0.0f && z[i] < 1.0f) inner.push_back(z[i]);
    if (!c.stats().overflow && int(inner.size()) <= kTableNodes) return inner;
  }
}

PrecompressedStep tabulate(const ObjectView& o, const TransferPoint* tf, double d0, double d1,
                           float eps) {
  std::vector<double> tau(kFineSteps + 1, 0.0);
  for (int k = 0; k < kFineSteps; ++k) {
    const double u = (k + 0.5) / kFineSteps;
    tau[size_t(k) + 1] =
        tau[size_t(k)] +
        evaluate_transfer(tf, o.transfer_count, d0 + (d1 - d0) * u).sigma / kFineSteps;
  }
  PrecompressedStep step{};
  for (float s : node_positions(tau, o.step, eps)) {
    const double x = double(s) * kFineSteps;
    const int k = std::min(int(x), kFineSteps - 1);
    step.s[step.count] = s;
    step.tau[step.count] = float(tau[size_t(k)] + (tau[size_t(k) + 1] - tau[size_t(k)]) * (x - k));
    ++step.count;
  }
  step.tau_end = float(tau[kFineSteps]);
  return step;
}

}  // namespace

PrecompressedTableData build_precompressed_tables(const SceneData& scene, int bins,
                                                  float table_eps) {
  const std::vector<ObjectView> objects = to_host_vector(scene.view().objects, scene.memory());
  const std::vector<TransferPoint> transfer = to_host_vector(scene.view().transfer, scene.memory());
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
    const auto centre = [&](int i) { return domain.x + (domain.y - domain.x) * (i + 0.5) / bins; };
    for (int i = 0; i < bins; ++i)
      for (int j = 0; j < bins; ++j)
        data.steps.push_back(tabulate(o, tf, centre(i), centre(j), table_eps));
  }
  return data;
}

}  // namespace dv
