// Deep shadow maps of every light of a scene, end to end: generation (engine/dsm/dsm_generation.h)
// into a storage strategy chosen by name (strategies/storage/), figures, and the kernel-side source
// the renderer and probe query (strategies/storage/dsm_device.h). The `dsm` shadow method wraps
// it; `deepvox dsm` (export) and the tests use it directly. The device memory pool is trimmed
// after each generation, so the scratch it needed is not held beside the maps.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/registry.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/dsm/dsm_generation.h"
#include "engine/scene/scene_view.h"
#include "strategies/storage/dsm_device.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

struct DsmSettings {
  std::string storage = "compact";
  StrategyParams storage_params;
  int resolution = 1024;
  float eps = 0.02f;
  bool bilinear = false;
  int subrays = 1;             // 4, 9, 16: jittered sub-rays per texel, averaged (pre-filtering)
  bool precompressed = false;  // volume steps from Hadwiger's pre-compressed tables
  int table_bins = 64;
  double step_scale = 1.0;  // multiplies the volumes' steps during generation
  double bias = -1.0;       // world units; < 0: 1e-4 of the scene diagonal
  double slope_bias = 3.0;
  ClusterSettings clusters;  // max_clusters > 1: clustered maps (light_clusters.h)
  int light = -1;            // >= 0: maps of this light only, whose source answers it as light 0
  // records() after a generation in several sets of faces too (a host copy of each set, made
  // as it is generated); without it only a generation in one set answers records().
  bool keep_records = false;
  int64_t face_set_bytes = kFaceSetBytes;  // what one set of faces may take (dsm_storage.h)

  // From parameters resolved against dsm_param_table() (every key present), and the same keys
  // written back: own_params() the table's keys, params() with the storage strategy that
  // created them (its name, its own keys as storage.KEY); read(params(...)) gives these
  // settings again.
  static DsmSettings read(const StrategyParams& p);
  nlohmann::json own_params() const;
  nlohmann::json params(const DsmStorage& storage) const;
};

// The parameters of the `dsm` shadow method (and of `auto`, which builds deep maps with them):
// keys, defaults (those of DsmSettings), ranges and descriptions. DeepShadowMaps checks its
// settings against it too, so direct users meet the same rules.
const ParamTable& dsm_param_table();

class DeepShadowMaps {
 public:
  // Creates the storage strategy (unknown names and parameters throw InputError).
  explicit DeepShadowMaps(DsmSettings settings);

  // Generates every light's maps (settings().light >= 0: that light's alone) for `scene`, which
  // lives in the memory of `backend`: the standard faces, or with clusters the faces of
  // plan_clusters(scene, camera).
  void generate(const SceneData& scene, Backend backend, const Camera* camera = nullptr);

  // The clustered layout these settings give for `scene` (settings().clusters.max_clusters > 1)
  // seen by `camera` (lispsm only; null: every object, plain light space).
  ClusteredLayout plan_clusters(const SceneData& scene, const Camera* camera) const;
  // Whether the last generation's clustering still serves `camera`: its hysteresis holds
  // (clustering_holds) or clustering anew gives the same clusters and frusta. True unclustered.
  bool clustering_holds(const SceneData& scene, const Camera* camera) const;
  // The clustering of the last generation; null without clusters.
  const ClusteredLayout* clusters() const { return clustered_ ? &clusters_ : nullptr; }
  int resolution() const { return clustered_ ? clusters_.resolution : settings_.resolution; }

  // Valid after generate(), while this object and the scene live.
  DsmSource source() const { return source_; }
  const DsmSettings& settings() const { return settings_; }
  const DsmStorage& storage() const { return *storage_; }
  const LightMapLayout& layout() const { return generation_->layout(); }
  const std::vector<DsmPass>& passes() const { return passes_; }
  double generation_milliseconds() const;  // all passes, rasterization included
  // The per-texel records on the host (DsmRecords::host: copied from the backend on the first
  // call after a generation in one set; after one in several sets, only with
  // settings().keep_records). figures() needs no copy.
  const std::vector<DsmTexelRecord>& records() const { return records_.host(); }
  const nlohmann::json& figures() const { return figures_; }
  int64_t fragments() const { return generation_->fragments(); }
  int generations() const { return generations_; }

 private:
  DsmSettings settings_;
  std::unique_ptr<DsmStorage> storage_;
  std::unique_ptr<DsmGeneration> generation_;
  DsmRecords records_;
  Buffer<DsmColourTexel> colour_texels_;  // the colour side channel; empty for grey scenes
  std::vector<DsmPass> passes_;
  nlohmann::json figures_;
  DsmSource source_{};
  ClusteredLayout clusters_;
  bool clustered_ = false;
  int generations_ = 0;
};

}  // namespace dv
