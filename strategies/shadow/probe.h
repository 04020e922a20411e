// Batch shadow queries: the transmittance of every light at every point through any shadow
// method, on the CPU threads or as a CUDA kernel (the same code). `deepvox probe` uses it, and
// comparing two methods' answers at the same points is how accuracy is measured.
#pragma once

#include <cstdint>
#include <vector>

#include "cuda/execute.h"
#include "engine/scene/scene_view.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

struct ProbeResults {
  std::vector<double> transmittance;  // [point * light_count + light]: luminance of rgb
  std::vector<dvec3> rgb;             // the same answers per colour channel
  std::vector<uint32_t> flags;        // per answer: the method's cursor flags (oracle: OracleFlag)
  int light_count = 0;
  double milliseconds = 0.0;  // the query kernel alone
};

// `scene` must live in the memory of `backend` (host for cpu, device for cuda). `camera`:
// what the method prepares for (ShadowMethod::prepare: focused maps), null as `deepvox probe`.
ProbeResults probe_transmittance(Backend backend, const SceneData& scene, ShadowMethod& method,
                                 const std::vector<dvec3>& points, const Camera* camera = nullptr);

}  // namespace dv
