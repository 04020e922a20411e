// How `deepvox advise` measures one shadow configuration on the user's scene, with
// the suite harness's own pieces (SceneCache's stratified probes with the exact oracle and
// reference render, shadow_measure.h's timed repetitions and memory figure, image error): per
// stratum of the probe points (probe_strata.h: lit, umbra, partial, media; camera-visible first,
// then the light's view of the receivers where the camera sees too little shadow) the count,
// p95 and max of |T' - T| over every (point, light) sample, the image RMSE and edge error at a
// small size against the oracle's render, the warm frame time (median generation + median
// render on the chosen backend) and the method's bytes. The bound is checked against every
// stratum: where shadows cover little of the view, a p95 over the camera's points alone is 0
// for every configuration whatever it does in the shadows.
// verify() repeats the error measurement on fresh probe points (another seed) for the pick;
// interleaved_frame_ms() times configurations again, alternating them, for the final choice.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cuda/execute.h"
#include "experiments/advise/advise_search.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/shadow_measure.h"

namespace dv {

struct AdviseSettings {
  int width = 0, height = 0;  // the small image; 0: the camera's, scaled to at most 320 wide
  int probes = 2000;          // camera-visible probe points (and as many inside media)
  int stratum_min = 200;      // samples wanted per surface stratum (probe_strata.h)
  uint64_t seed = 1;          // the search's points; verify() takes another
  int repeat = 3;             // timed repetitions after a warm-up
};

class AdviseMeasurer {
 public:
  AdviseMeasurer(SceneCache& cache, std::string scene_path, AdviseSettings settings);
  // The search's measurement of `config` (a failure, such as a storage's limit, comes back as
  // ok = false with its message).
  AdviseMeasurement measure(const ShadowConfig& config);
  // The error of `config` at fresh points (seed `seed`), its time and bytes measured anew.
  AdviseMeasurement verify(const ShadowConfig& config, uint64_t seed);
  // Frame times only (median generation + median render, ms, as measure() takes them) of each
  // config in `rounds` interleaved rounds (interleaved_rounds): per config its time per round,
  // +infinity for a round where it failed.
  std::vector<std::vector<double>> interleaved_frame_ms(const std::vector<ShadowConfig>& configs,
                                                        int rounds);
  // Which casters the lights reach (advise_space's families).
  AdviseSceneKind kind() const;
  int width() const { return settings_.width; }
  int height() const { return settings_.height; }
  int light_count() const;
  // The exact oracle's time for the search's probe points and reference render, ms.
  double oracle_ms();
  // The stratified probe points of `seed` (the search's: settings' seed).
  const StratifiedProbes& strata(uint64_t seed);

 private:
  AdviseMeasurement measure_with(const ShadowConfig& config, uint64_t seed);
  // The scene's camera at the measurements' image size.
  Camera camera() const;
  // `config` generated and rendered from `camera`: a warm-up, then settings_.repeat timed
  // repetitions of each (throws the strategy's Error when it fails).
  TimedRepeats timed(const ShadowConfig& config, const Camera& camera);
  SceneCache& cache_;
  std::string path_;
  AdviseSettings settings_;
  bool casters_ = false;  // some light reaches a caster
};

}  // namespace dv
