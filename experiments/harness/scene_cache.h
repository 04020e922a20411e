// What a suite run computes once and shares between experiments: loaded scenes, their kernel
// data (in host memory, and in device memory on CUDA), probe points with the exact oracle's
// answers, and reference renders. Keyed by resolved scene path and the settings that shape them.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "core/image.h"
#include "cuda/execute.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"
#include "experiments/harness/probe_points.h"

namespace dv {

struct ProbeSet {
  ProbePoints points;
  std::vector<double> exact;  // [point * light_count + light], the oracle
  std::vector<uint32_t> exact_flags;
  int light_count = 0;
  double oracle_ms = 0.0;
};

struct ReferenceRender {
  Image image;
  double milliseconds = 0.0;
  std::string png;  // path relative to the run folder, once written
};

class SceneCache {
 public:
  explicit SceneCache(Backend backend) : backend_(backend) {}
  Backend backend() const { return backend_; }

  const Scene& scene(const std::string& path);
  const SceneData& host_data(const std::string& path);
  const SceneData& data(const std::string& path);  // in the backend's memory
  const ProbeSet& probes(const std::string& path, int count, double medium_fraction, uint64_t seed,
                         double isosurface = -1.0);
  // The raster renderer with the exact oracle's shadows at width x height.
  ReferenceRender& reference(const std::string& path, int width, int height);

 private:
  struct Entry {
    Scene scene;
    std::unique_ptr<SceneData> host, device;
  };
  Entry& entry(const std::string& path);

  Backend backend_;
  std::map<std::string, Entry> scenes_;
  std::map<std::tuple<std::string, int, double, uint64_t, double>, ProbeSet> probes_;
  std::map<std::tuple<std::string, int, int>, ReferenceRender> references_;
};

}  // namespace dv
