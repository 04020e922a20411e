// What `deepvox dsm` exports from generated deep shadow maps: every face's nodes with its
// matrix, light and face index as a DeepMapFile (written as a deep EXR by render/io/deep_exr.h),
// and the layers (stored nodes) per texel and the face labels the heatmap draws
// (render/io/layer_heatmap.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/io/deep_exr.h"
#include "strategies/storage/deep_shadow_maps.h"

namespace dv {

// Needs a storage that copies its nodes out (`compact`).
DeepMapFile deep_map_file(const DeepShadowMaps& maps, const std::string& commit);

// One count per texel of the layout, texel index face * res^2 + y * res + x.
std::vector<int32_t> stored_layers(const DeepShadowMaps& maps);
// One label per face of the layout, in layout order: "L<light>" for a one-face light,
// "L<light> +X" ... "L<light> -Z" for the faces of an omni light (named by their axis).
std::vector<std::string> face_labels(const LightMapLayout& layout);

}  // namespace dv
