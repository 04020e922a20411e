// What a suite run computes once and shares between experiments: loaded scenes, their kernel
// data (in host memory, and in device memory on CUDA), probe points with the exact oracle's
// answers, reference renders, and the camera's view (the surface each pixel sees, its depth)
// with the camera-visible probe points drawn from it, and the stratified probe points
// (probe_strata.h) of the camera's view. Keyed by resolved scene path and the settings
// that shape them.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "core/image.h"
#include "cuda/execute.h"
#include "engine/raster/visible_surface.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"
#include "experiments/harness/probe_points.h"
#include "experiments/harness/probe_strata.h"

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

// What the scene's camera at a size sees: computed on the host (Backend::cpu) whatever the
// run's backend, so the points and depths are the same on every machine.
struct CameraSight {
  VisibleSurface surface;
  std::vector<double> depth;  // per pixel: image_metrics.h's view_depths
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
  // The scene's camera at width x height: what each pixel sees.
  const CameraSight& sight(const std::string& path, int width, int height);
  // `count` points of sight(path, width, height) (make_visible_probe_points) with the oracle.
  const ProbeSet& visible_probes(const std::string& path, int width, int height, int count,
                                 uint64_t seed);
  // The stratified points of the camera's view at width x height (make_stratified_probes, with
  // the media points when some object has an interior).
  const StratifiedProbes& stratified_probes(const std::string& path, int width, int height,
                                            const StrataSettings& settings);

 private:
  // The scene's camera at `width` x `height` (the experiment's image size).
  Camera camera_at(const std::string& path, int width, int height);
  struct Entry {
    Scene scene;
    std::unique_ptr<SceneData> host, device;
  };
  Entry& entry(const std::string& path);
  ProbeSet with_oracle(const std::string& path, ProbePoints points);

  Backend backend_;
  std::map<std::string, Entry> scenes_;
  std::map<std::tuple<std::string, int, double, uint64_t, double>, ProbeSet> probes_;
  std::map<std::tuple<std::string, int, int>, ReferenceRender> references_;
  std::map<std::tuple<std::string, int, int>, CameraSight> sights_;
  std::map<std::tuple<std::string, int, int, int, uint64_t>, ProbeSet> visible_probes_;
  std::map<std::tuple<std::string, int, int, int, int, uint64_t>, StratifiedProbes> strata_;
};

}  // namespace dv
