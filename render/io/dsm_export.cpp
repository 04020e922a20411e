// Export views of generated deep shadow maps (see dsm_export.h).
#include "render/io/dsm_export.h"

#include <algorithm>
#include <cmath>

namespace dv {

DeepMapFile deep_map_file(const DeepShadowMaps& maps, const std::string& commit) {
  const DsmHostNodes host = maps.storage().host_nodes();
  const LightMapLayout& layout = maps.layout();
  DeepMapFile file;
  file.eps = maps.settings().eps;
  file.commit = commit;
  for (size_t l = 0; l < layout.lights.size(); ++l)
    for (int i = 0; i < layout.lights[l].face_count; ++i) {
      const ShadowFace& sf = layout.faces[size_t(layout.lights[l].first_face) + i];
      DeepMapFace f;
      f.resolution = maps.resolution();
      const double* m = &sf.projection.world_to_clip[0][0];
      std::copy_n(m, 16, f.world_to_clip.begin());
      f.light = int(l);
      f.face = i;
      f.orthographic = sf.orthographic;
      const int64_t first = host.offsets[sf.offset];
      const int64_t last = host.offsets[sf.offset + layout.texels_per_face];
      for (int64_t t = 0; t <= layout.texels_per_face; ++t)
        f.offsets.push_back(host.offsets[sf.offset + t] - first);
      f.nodes.assign(host.nodes.begin() + first, host.nodes.begin() + last);
      file.faces.push_back(std::move(f));
    }
  return file;
}

std::vector<int32_t> stored_layers(const DeepShadowMaps& maps) {
  std::vector<int32_t> layers;
  layers.reserve(maps.records().size());
  for (const DsmTexelRecord& r : maps.records()) layers.push_back(r.stored);
  return layers;
}

std::vector<std::string> face_labels(const LightMapLayout& layout) {
  std::vector<std::string> labels;
  for (size_t l = 0; l < layout.lights.size(); ++l)
    for (int i = 0; i < layout.lights[l].face_count; ++i) {
      std::string label = "L";
      label += std::to_string(l);
      if (layout.lights[l].face_count > 1) {
        const dvec3 a = layout.faces[size_t(layout.lights[l].first_face) + i].axis;
        const int k = std::abs(a.x) >= std::abs(a.y) && std::abs(a.x) >= std::abs(a.z) ? 0
                      : std::abs(a.y) >= std::abs(a.z)                                 ? 1
                                                                                       : 2;
        label += std::string(a[k] > 0.0 ? " +" : " -") + "XYZ"[k];
      }
      labels.push_back(label);
    }
  return labels;
}

}  // namespace dv
